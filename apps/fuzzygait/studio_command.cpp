// `fuzzygait studio`: serves the studio (docs/studio.md) on 127.0.0.1 until Ctrl-C.
#include <pthread.h>
#include <signal.h>

#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "fuzzygait/studio/server.hpp"
#include "fuzzygait/studio/studio.hpp"

namespace fuzzygait::cli {
namespace {

struct StudioCommandOptions {
  studio::StudioOptions studio;
  std::vector<std::string> folders;
  std::string workspace = "studio-sets";
  studio::ServerOptions server;
};

// Ctrl-C (SIGINT) and SIGTERM stop the server: they are blocked in every thread and one thread
// waits for them, so the server stops from ordinary code rather than a signal handler.
class StopOnSignal {
 public:
  explicit StopOnSignal(studio::Server& server) {
    sigset_t signals = stop_signals();
    pthread_sigmask(SIG_BLOCK, &signals, &previous_);
    waiter_ = std::thread([&server, signals] {
      int received = 0;
      sigwait(&signals, &received);
      if (received != SIGUSR1) server.stop();
    });
  }
  ~StopOnSignal() {
    pthread_kill(waiter_.native_handle(), SIGUSR1);  // ends the wait when the server stopped first
    waiter_.join();
    pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

 private:
  static sigset_t stop_signals() {
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    sigaddset(&signals, SIGUSR1);
    return signals;
  }
  sigset_t previous_;
  std::thread waiter_;
};

}  // namespace

void add_studio_command(CLI::App& app) {
  auto o = std::make_shared<StudioCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "studio", "Serve the studio: shape a controller set in a browser while the character walks");
  cmd->add_option("--port", o->server.port, "Port to listen on (default 8642; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--controllers", o->folders,
                  "Controller set folders to open, trained sets too (the first opens first)");
  cmd->add_option("--style", o->studio.style,
                  "Built-in set opened first when no folder is given (default: default)");
  cmd->add_option("--workspace", o->workspace,
                  "Folder the page's Save writes sets into (default studio-sets)");
  cmd->add_option("--terrain", o->studio.terrains,
                  "Grounds offered besides the built-in ones, as walk --terrain spells them "
                  "(profile:FILE.csv too)");
  cmd->add_option("--step", o->studio.step, "Step length to start with, metres (default 0.70)");
  cmd->add_option("--stature", o->studio.stature, "Stature to start with, metres (default 1.75)");
  cmd->add_option("--host", o->server.host,
                  "Address to listen on (default 127.0.0.1: this machine only; any other exposes "
                  "the studio and its Save to the network)");
  cmd->add_option("--allow-host", o->server.allowed_hosts,
                  "Names or addresses a browser may reach the studio by besides 127.0.0.1, "
                  "localhost and --host (this machine's address on the network, with --host "
                  "0.0.0.0); requests naming any other host are refused");
  cmd->footer(
      "Prints the address to open in a browser and serves until Ctrl-C. The page's Save writes\n"
      "a set to WORKSPACE/NAME (manifest.json and FLL files, as controllers/ holds them).");
  cmd->callback([o]() {
    for (const std::string& folder : o->folders)
      o->studio.folders.emplace_back(folder);
    o->studio.workspace = o->workspace;
    studio::Studio session(o->studio);
    studio::Server server(session, o->server);
    StopOnSignal stop(server);
    if (!server.loopback()) {
      std::cerr << "fuzzygait studio: warning: listening on " << o->server.host
                << ", not loopback: anyone who reaches this machine can edit sets and save them "
                   "into the workspace (requests must name it 127.0.0.1, localhost, [::1], "
                << o->server.host << " or an --allow-host name)" << std::endl;
    }
    std::cout << "fuzzygait studio: open " << server.address() << " in a browser (Ctrl-C stops)"
              << std::endl;
    if (!server.run()) throw std::runtime_error("the studio stopped listening");
    std::cout << "fuzzygait studio: stopped" << std::endl;
  });
}

}  // namespace fuzzygait::cli
