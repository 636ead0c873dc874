// How the studio's server holds its connections, in front of cpp-httplib 0.11's request parser:
// a request's head read within bounds (cpp-httplib would keep a header line of any length whole
// in memory), a deep listen queue, and a pool of workers that neither hangs nor grows when more
// connections come than it has workers.
#pragma once

#include <httplib.h>

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <ctime>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace fuzzygait::studio::detail {

struct ConnectionLimits {
  // The request line's bytes (longer: 414) and a header line's (longer: 431), with its CRLF.
  std::size_t longest_request_line = 8 * 1024;
  std::size_t longest_header_line = 8 * 1024;
  // The request line and the headers together (more: 431).
  std::size_t largest_head = 64 * 1024;
  // A request's head must arrive within this of its first byte (a client sending a byte now and
  // then would otherwise hold a worker for good); its body within kSlowestRequest.
  int head_seconds = 2;
  // Between requests a connection that sends nothing for this long is closed; sooner when
  // accepted connections wait for a worker.
  int idle_seconds = 2;
  int write_seconds = 5;
  std::size_t keep_alive_requests = 1000;
  // Connections served at once, and accepted ones that may wait for a worker; past those, a
  // connection is answered 503 at once and closed.
  int workers = 64;
  int waiting = 64;
  // Queued connections the kernel holds before the server accepts them (cpp-httplib 0.11 asks
  // for 5, so a burst of a browser's connections beyond them is refused by the kernel).
  int listen_backlog = 256;
};

// The longest a request may take to arrive, head and body.
inline constexpr int kSlowestRequest = 30;

// A pool of `workers` threads serving connections, with at most `waiting` connections queued for
// them. A connection past those goes to a refusal thread, on which GuardedServer answers it 503.
class ConnectionPool : public httplib::TaskQueue {
 public:
  ConnectionPool(int workers, int waiting);
  ~ConnectionPool() override;
  ConnectionPool(const ConnectionPool&) = delete;
  ConnectionPool& operator=(const ConnectionPool&) = delete;

  void enqueue(std::function<void()> serve) override;
  void shutdown() override;

  // Whether accepted connections wait for a worker now (idle connections then make room).
  bool has_waiting() const { return waiting_now_.load() > 0; }
  // Whether the calling thread is the pool's refusal thread.
  static bool refusing_on_this_thread();

 private:
  void work(std::deque<std::function<void()>>& queue);

  const std::size_t most_waiting_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queued_;
  std::deque<std::function<void()>> refused_;
  std::atomic<int> waiting_now_{0};
  bool stopping_ = false;
  std::vector<std::thread> workers_;
  std::thread refuser_;
};

// cpp-httplib's server with its connections served by GuardedServer's loop: each request's head
// read through a stream that bounds it, idle connections closed early while others wait, and a
// connection past the pool's queue answered 503.
class GuardedServer : public httplib::Server {
 public:
  explicit GuardedServer(const ConnectionLimits& limits);

  // Headers ("Name: value\r\n" each) added to the answers written here (414, 431, 503), which do
  // not pass through cpp-httplib's handlers.
  void set_refusal_headers(std::string headers) { refusal_headers_ = std::move(headers); }
  // After binding: the listen queue deepened to limits.listen_backlog. False when it failed.
  bool deepen_listen_queue();

 private:
  bool process_and_close_socket(socket_t sock) override;
  // Waits for the next request's first byte: false when the connection stays idle for
  // idle_seconds, when connections wait for a worker (after a short grace), or when stopping.
  bool wait_for_request(socket_t sock) const;

  ConnectionLimits limits_;
  std::string refusal_headers_;
  ConnectionPool* pool_ = nullptr;  // made by new_task_queue, owned by httplib::Server
};

// The answer written for a refusal the server makes before cpp-httplib reads the request.
std::string refusal_response(int status, const char* reason, const std::string& field,
                             const std::string& message, const std::string& extra_headers);

}  // namespace fuzzygait::studio::detail
