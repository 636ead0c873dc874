// The studio's HTTP server: the page's files (embedded in the program) and the API of studio.hpp
// as JSON over plain HTTP requests (cpp-httplib). One Studio serves every request, one at a time.
//
//   GET  /                      the page; /src/..., /style.css its modules; /vendor/... the npm
//                               packages it imports (three.js, uPlot, lil-gui)
//   GET  /api/state, /api/walk  Studio::state(), Studio::walk()
//   POST /api/edit, /api/rules, /api/term, /api/fired, /api/settings, /api/undo, /api/redo,
//        /api/history, /api/open, /api/save, /api/compare
//                               the Studio call of that name, the body its request (/api/rules
//                               up to Limits::kLargestRulesBody, the others max_body)
//   GET  /api/download/FILE     Studio::download(FILE), as an attachment
//
// Refusals answer with a 4xx status and {"error", "field", "status"}: a path with '..' (400), an
// unknown path (404), a method other than GET, HEAD and POST (405), a POST whose body is not JSON
// (400) or not of Content-Type application/json (415), a body over the size limit in any transfer
// encoding (413; the rest of it is read and dropped, or the connection closed), a Host header that
// does not name this server or an Origin of another site, on any address it listens on (403:
// another site's page cannot drive the studio, DNS rebinding included), a request line over 8 KiB
// (414), a header line over 8 KiB or headers over 64 KiB (431, read no further), a head that takes
// longer than idle_seconds to arrive (400), more connections than threads and waiting together
// (503 with Retry-After), and every RequestError.
// Every answer carries a Content-Security-Policy (frame-ancestors 'none'), X-Frame-Options: DENY
// and X-Content-Type-Options: nosniff.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fuzzygait/studio/studio.hpp"

namespace fuzzygait::studio {

struct ServerOptions {
  std::string host = "127.0.0.1";    // loopback: only this machine reaches it
  int port = 8642;                   // 0: any free port (port() tells which)
  std::size_t max_body = 64 * 1024;  // bytes of a request body, however it is sent
  int threads = 64;                  // connections served at once
  // Connections that may wait for one of the threads (idle ones are then closed to make room);
  // one more is answered 503 with Retry-After at once.
  int waiting = 64;
  int listen_backlog = 256;  // connections the kernel queues before the server accepts them
  int idle_seconds = 2;      // a connection that sends nothing for this long is closed
  // Names a browser may reach the server by besides 127.0.0.1, localhost, [::1] and `host` (the
  // machine's own address or name when `host` is 0.0.0.0); a request's Host must be one of them
  // with the port, and an Origin http:// one of them with the port.
  std::vector<std::string> allowed_hosts;
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
  // Whether it listens on a loopback address only (127.x.x.x, ::1, localhost).
  bool loopback() const;
  // "http://127.0.0.1:PORT/" (the host it listens on; 127.0.0.1 for 0.0.0.0 and ::)
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
