// cli/commands.hpp — the subcommands of `nut`. Each adds itself to the app and sets the exit code
// when it runs, and the checks they share.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace nut::cli {

// Exit codes, the same for every command (README.md, Exit codes): 0 success; 1 the input was read
// but is invalid (not an HNI, a mesh with no faces, images of different sizes); 2 the command could
// not run as asked: a usage error (unknown command or flag, a missing or malformed argument, an
// output name whose extension is not what the command writes) or a file that cannot be read or
// written.
enum ExitCode { kOk = 0, kInvalid = 1, kUsage = 2, kUnreadable = 2 };

// The exit codes as every command's help states them.
inline constexpr const char* kExitCodesHelp =
    "Exit status: 0 success, 1 invalid input, 2 usage error or a file that cannot be read or written.";

// Prints an error as every command does, one line `error: <where>: <reason>` on stderr, and
// returns `code`.
int fail(const std::string& message, int code);

// The extension of `path` in lower case with its dot (".png"); "" when it has none.
std::string lowerExtension(const std::string& path);

// A check run while the command line is parsed, before any work: the path must end in
// `extension` (lower case, with its dot; any case is accepted), because the command writes
// `format` there. Otherwise: `--depth: out.png: writes PFM; expected a name ending in .pfm`.
CLI::Validator outputExtension(const std::string& extension, const std::string& format);

void addInfoCommand(CLI::App& app, int& exitCode);
void addValidateCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addExportMeshCommand(CLI::App& app, int& exitCode);
void addRenderMeshCommand(CLI::App& app, int& exitCode);
void addCompareCommand(CLI::App& app, int& exitCode);
void addConvertCommand(CLI::App& app, int& exitCode);
void addGrammarCommand(CLI::App& app, int& exitCode);
void addCityCommand(CLI::App& app, int& exitCode);

}  // namespace nut::cli
