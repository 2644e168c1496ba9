// cli/commands.hpp — the subcommands of `nut`. Each adds itself to the app and sets the exit code
// when it runs. Exit codes: 0 success, 1 usage error or invalid input, 2 unreadable input or I/O.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace nut::cli {

enum ExitCode { kOk = 0, kInvalid = 1, kUsage = 1, kUnreadable = 2 };

// Prints an error as every command does, one line `error: <where>: <reason>` on stderr, and
// returns `code`.
int fail(const std::string& message, int code);

void addInfoCommand(CLI::App& app, int& exitCode);
void addValidateCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addExportMeshCommand(CLI::App& app, int& exitCode);
void addRenderMeshCommand(CLI::App& app, int& exitCode);
void addCompareCommand(CLI::App& app, int& exitCode);
void addConvertCommand(CLI::App& app, int& exitCode);

}  // namespace nut::cli
