// fuzzygait: command-line front end of the library.
#include <exception>
#include <iostream>
#include <stdexcept>

#include "commands.hpp"
#ifndef FUZZYGAIT_HAVE_STUDIO
#include "studio_missing.hpp"
#endif

int main(int argc, char** argv) {
  CLI::App app{"fuzzygait: real-time procedural gait animation driven by fuzzy controllers"};
  app.require_subcommand(1);
  fuzzygait::cli::add_walk_command(app);
  fuzzygait::cli::add_eval_command(app);
  fuzzygait::cli::add_mocap_command(app);
  fuzzygait::cli::add_fuzzy_command(app);
  fuzzygait::cli::add_tune_command(app);
  fuzzygait::cli::add_tune_terrain_command(app);
#ifdef FUZZYGAIT_HAVE_STUDIO
  fuzzygait::cli::add_studio_command(app);
#else
  // A build without the studio says why rather than not knowing the command.
  app.add_subcommand("studio", "Not in this build: " FUZZYGAIT_STUDIO_MISSING)
      ->allow_extras()
      ->callback([] {
        throw std::runtime_error(
            "this fuzzygait was built without the studio: " FUZZYGAIT_STUDIO_MISSING
            "; its npm packages are installed when CMake configures the build: configure "
            "again where registry.npmjs.org can be reached");
      });
#endif
  fuzzygait::cli::add_train_command(app);
  int status = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    status = app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "fuzzygait: error: " << e.what() << "\n";
    status = 1;
  }
  // What was printed must have arrived: a full disk under `> file` (or a closed pipe, where
  // SIGPIPE is ignored) would otherwise end in success with the report or the table cut short.
  if (!std::cout.flush()) {
    std::cerr << "fuzzygait: error: cannot write to standard output\n";
    return status != 0 ? status : 1;
  }
  return status;
}
