// `nut validate FILE.png`: exit 0 when the file is a valid HNI, 1 when it is not (with the
// reason), 2 when it cannot be read as a PNG (or the command line is wrong).
#include <cstdio>
#include <memory>
#include <string>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>

#include "commands.hpp"

namespace nut::cli {

void addValidateCommand(CLI::App& app, int& exitCode) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("validate", "Check that a PNG is a valid HNI (every rule of docs/FORMAT.md)");
  cmd->add_option("file", *path, "HNI image (PNG)")->required();
  cmd->footer("Example:\n  nut validate samples/hni/building.png\n\n"
              "Exit status: 0 valid, 1 invalid (with the reason), 2 unreadable or a usage error.");
  cmd->callback([path, &exitCode] {
    auto png = readPng(*path);
    if (!png) {
      exitCode = fail(png.error().message, kUnreadable);
      return;
    }
    if (Status s = validate(png->image); !s) {
      exitCode = fail(*path + ": invalid HNI: " + s.error().message, kInvalid);
      return;
    }
    std::printf("%s: valid HNI, %dx%d px\n", path->c_str(), png->image.width, png->image.height);
    exitCode = kOk;
  });
}

}  // namespace nut::cli
