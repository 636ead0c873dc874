// The studio's HTTP server: the page's files (embedded in the program) and the API of studio.hpp
// as JSON over plain HTTP requests (cpp-httplib). One Studio serves every request, one at a time.
//
//   GET  /                      the page; /src/..., /style.css its modules; /vendor/... the npm
//                               packages it imports (three.js, uPlot, lil-gui)
//   GET  /api/state, /api/walk  Studio::state(), Studio::walk()
//   POST /api/edit, /api/settings, /api/undo, /api/redo, /api/open, /api/save, /api/compare
//                               the Studio call of that name, the body its request
//   GET  /api/download/FILE     Studio::download(FILE), as an attachment
//
// Refusals answer with a 4xx status and {"error", "field", "status"}: a path with '..' (400), an
// unknown path (404), a POST whose body is not JSON (400) or not of Content-Type
// application/json (415), a body over the size limit (413), a Host or Origin header that is not
// the server's own while it listens on loopback (403: another site's page cannot drive the
// studio), and every RequestError.
#pragma once

#include <memory>
#include <string>

#include "fuzzygait/studio/studio.hpp"

namespace fuzzygait::studio {

struct ServerOptions {
  std::string host = "127.0.0.1";    // loopback: only this machine reaches it
  int port = 8642;                   // 0: any free port (port() tells which)
  std::size_t max_body = 64 * 1024;  // bytes of a request body
  int threads = 16;                  // connections served at once
};

class Server {
 public:
  // Binds the port. Throws std::runtime_error naming the address when it cannot (in use, no such
  // address); std::invalid_argument for options out of range.
  Server(Studio& studio, const ServerOptions& options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  int port() const;
  // "http://127.0.0.1:PORT/"
  std::string address() const;
  // Serves until stop() is called (from another thread). Returns false when listening failed.
  bool run();
  // Makes run() return; safe from any thread, before or during run().
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fuzzygait::studio
