// `nut`: the command-line tool. Parses the subcommand and hands over; errors are one line.
#include <cstdio>
#include <exception>

#include "commands.hpp"

int nut::cli::fail(const std::string& message, int code) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  return code;
}

int main(int argc, char** argv) {
  CLI::App app{"nut: Non-Uniform Texture toolkit (HNI images of buildings)"};
  app.require_subcommand(1);
  app.footer(
      "Examples:\n  nut info samples/hni/building.png --json\n  nut validate samples/hni/facade.png\n\n"
      "Run `nut <command> --help` for the options of a command.");
  int exitCode = nut::cli::kOk;
  nut::cli::addInfoCommand(app, exitCode);
  nut::cli::addValidateCommand(app, exitCode);
  nut::cli::addRenderCommand(app, exitCode);
  nut::cli::addExportMeshCommand(app, exitCode);
  nut::cli::addRenderMeshCommand(app, exitCode);
  nut::cli::addCompareCommand(app, exitCode);
  nut::cli::addConvertCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    return nut::cli::fail(std::string(e.what()) + " (see nut --help)", nut::cli::kUsage);
  } catch (const std::exception& e) {
    return nut::cli::fail(e.what(), nut::cli::kUnreadable);
  }
  return exitCode;
}
