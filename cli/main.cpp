// `nut`: the command-line tool. Parses the subcommand and hands over; errors are one line, and the
// exit codes are those of commands.hpp.
#include <cctype>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "commands.hpp"

namespace nut::cli {

int fail(const std::string& message, int code) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  return code;
}

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

CLI::Validator outputExtension(const std::string& extension, const std::string& format) {
  return CLI::Validator(
      [extension, format](std::string& path) {
        if (lowerExtension(path) == extension) return std::string();
        return path + ": writes " + format + "; expected a name ending in " + extension;
      },
      "");
}

namespace {

// The first argument that is not a flag names the command (`nut` itself takes only flags). CLI11
// would report an unknown one as a missing command; this names it and the commands there are.
bool isUnknownCommand(const CLI::App& app, int argc, char** argv, std::string& message) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.empty() || arg[0] == '-') continue;
    std::string names;
    for (const CLI::App* command : app.get_subcommands({})) {
      if (command->get_name() == arg) return false;
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    message = "unknown command '" + arg + "' (commands: " + names + "; see nut --help)";
    return true;
  }
  return false;
}

}  // namespace

}  // namespace nut::cli

int main(int argc, char** argv) {
  CLI::App app{"nut: Non-Uniform Texture toolkit (HNI images of buildings)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("nut ") + NUT_VERSION, "Print the version and exit");
  app.footer(
      "Examples:\n  nut info samples/hni/building.png --json\n  nut validate samples/hni/facade.png\n\n"
      "Run `nut <command> --help` for the options of a command.\n\n" +
      std::string(nut::cli::kExitCodesHelp));
  int exitCode = nut::cli::kOk;
  nut::cli::addInfoCommand(app, exitCode);
  nut::cli::addValidateCommand(app, exitCode);
  nut::cli::addRenderCommand(app, exitCode);
  nut::cli::addExportMeshCommand(app, exitCode);
#if NUT_HAVE_EMBREE
  nut::cli::addRenderMeshCommand(app, exitCode);
#endif
  nut::cli::addCompareCommand(app, exitCode);
  nut::cli::addGrammarCommand(app, exitCode);
  nut::cli::addCityCommand(app, exitCode);
#if NUT_HAVE_CONVERTER
  nut::cli::addConvertCommand(app, exitCode);
#endif
  if (std::string message; nut::cli::isUnknownCommand(app, argc, argv, message))
    return nut::cli::fail(message, nut::cli::kUsage);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::printf("%s\n", e.what());
    return 0;
  } catch (const CLI::ParseError& e) {
    return nut::cli::fail(std::string(e.what()) + " (see nut --help)", nut::cli::kUsage);
  } catch (const std::exception& e) {
    return nut::cli::fail(e.what(), nut::cli::kUnreadable);
  }
  return exitCode;
}
