#include "connections.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <nlohmann/json.hpp>

namespace fuzzygait::studio::detail {
namespace {

using Clock = std::chrono::steady_clock;

thread_local bool refusal_thread = false;

// Milliseconds left until `deadline`, at least 0.
int millis_until(Clock::time_point deadline) {
  const auto left =
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(left, 0, 60'000));
}

bool poll_for(socket_t sock, short events, int millis) {
  pollfd p{sock, events, 0};
  int ready = 0;
  do {
    ready = poll(&p, 1, millis);
  } while (ready < 0 && errno == EINTR);
  return ready > 0;
}

bool send_all(socket_t sock, const std::string& bytes, int seconds) {
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(seconds);
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    if (!poll_for(sock, POLLOUT, millis_until(deadline))) return false;
    const ssize_t n = ::send(sock, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

// Closes after an answer written before the request was read whole: the sending side first, then
// what the client still sends is read for a moment (up to 1 MiB) and dropped, so that closing does
// not reset the connection before the client has read the answer.
void close_after_answer(socket_t sock, int linger_millis) {
  constexpr std::size_t kMostDropped = 1024 * 1024;
  ::shutdown(sock, SHUT_WR);
  const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(linger_millis);
  std::array<char, 16 * 1024> dropped;
  std::size_t total = 0;
  while (total < kMostDropped && poll_for(sock, POLLIN, millis_until(deadline))) {
    const ssize_t n = ::recv(sock, dropped.data(), dropped.size(), 0);
    if (n <= 0) break;
    total += static_cast<std::size_t>(n);
  }
  ::close(sock);
}

void address_of(socket_t sock, bool peer, std::string& ip, int& port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  auto* a = reinterpret_cast<sockaddr*>(&address);
  if ((peer ? getpeername(sock, a, &length) : getsockname(sock, a, &length)) != 0) return;
  std::array<char, NI_MAXHOST> host{};
  std::array<char, NI_MAXSERV> service{};
  if (getnameinfo(a, length, host.data(), host.size(), service.data(), service.size(),
                  NI_NUMERICHOST | NI_NUMERICSERV) == 0) {
    ip = host.data();
    port = std::atoi(service.data());
  }
}

// A connection as cpp-httplib reads it, bounding each request's head: its lines' lengths, its
// size and the time it takes to arrive. A head past a bound is answered here (414 or 431) and the
// read fails, so cpp-httplib stops; it writes nothing more.
class BoundedStream : public httplib::Stream {
 public:
  BoundedStream(socket_t sock, const ConnectionLimits& limits, const std::string& headers)
      : sock_(sock), limits_(limits), refusal_headers_(headers) {}

  // A new request's head begins (its first byte is there to read).
  void begin_head() {
    in_head_ = true;
    head_bytes_ = 0;
    line_bytes_ = 0;
    lines_ = 0;
    const Clock::time_point now = Clock::now();
    head_deadline_ = now + std::chrono::seconds(limits_.head_seconds);
    request_deadline_ = now + std::chrono::seconds(kSlowestRequest);
  }
  // cpp-httplib has read the head: the body follows, read within the request's deadline.
  void end_head() { in_head_ = false; }
  bool refused() const { return refused_; }
  bool has_buffered() const { return start_ < end_; }

  bool is_readable() const override {
    return start_ < end_ || poll_for(sock_, POLLIN, millis_until(read_deadline()));
  }
  bool is_writable() const override {
    return !refused_ && poll_for(sock_, POLLOUT, limits_.write_seconds * 1000);
  }

  ssize_t read(char* out, size_t size) override {
    if (refused_) return -1;
    if (start_ == end_) {
      if (!poll_for(sock_, POLLIN, millis_until(read_deadline()))) return -1;
      const ssize_t n = ::recv(sock_, buffer_.data(), buffer_.size(), 0);
      if (n <= 0) return n;
      start_ = 0;
      end_ = static_cast<std::size_t>(n);
    }
    const std::size_t count = std::min(size, end_ - start_);
    if (in_head_ && !count_head(count)) return -1;
    std::copy_n(buffer_.data() + start_, count, out);
    start_ += count;
    return static_cast<ssize_t>(count);
  }

  ssize_t write(const char* data, size_t size) override {
    if (!is_writable()) return -1;
    return ::send(sock_, data, size, MSG_NOSIGNAL);
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address_of(sock_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address_of(sock_, false, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  Clock::time_point read_deadline() const {
    const Clock::time_point idle = Clock::now() + std::chrono::seconds(limits_.idle_seconds);
    return std::min(idle, in_head_ ? head_deadline_ : request_deadline_);
  }

  // Counts the next `count` buffered bytes of the head; false (and answered) past a bound.
  bool count_head(std::size_t count) {
    for (std::size_t i = start_; i < start_ + count; ++i) {
      ++head_bytes_;
      ++line_bytes_;
      const bool request_line = lines_ == 0;
      const std::size_t longest =
          request_line ? limits_.longest_request_line : limits_.longest_header_line;
      if (line_bytes_ > longest) {
        return refuse(
            request_line ? 414 : 431,
            request_line ? "URI Too Long" : "Request Header Fields Too Large",
            request_line ? "the request line is longer than " : "a header line is longer than ",
            longest);
      }
      if (head_bytes_ > limits_.largest_head) {
        return refuse(431, "Request Header Fields Too Large", "the request's headers exceed ",
                      limits_.largest_head);
      }
      if (buffer_[i] == '\n') {
        ++lines_;
        line_bytes_ = 0;
      }
    }
    return true;
  }

  bool refuse(int status, const char* reason, const std::string& what, std::size_t bound) {
    refused_ = true;
    send_all(sock_,
             refusal_response(status, reason, "header", what + std::to_string(bound) + " bytes",
                              refusal_headers_),
             limits_.write_seconds);
    return false;
  }

  socket_t sock_;
  const ConnectionLimits& limits_;
  const std::string& refusal_headers_;
  std::array<char, 4096> buffer_{};
  std::size_t start_ = 0;
  std::size_t end_ = 0;
  bool in_head_ = true;
  bool refused_ = false;
  std::size_t head_bytes_ = 0;
  std::size_t line_bytes_ = 0;
  std::size_t lines_ = 0;
  Clock::time_point head_deadline_ = Clock::now();
  Clock::time_point request_deadline_ = Clock::now();
};

}  // namespace

std::string refusal_response(int status, const char* reason, const std::string& field,
                             const std::string& message, const std::string& extra_headers) {
  const std::string body =
      nlohmann::json{{"error", message}, {"field", field}, {"status", status}}.dump();
  return "HTTP/1.1 " + std::to_string(status) + " " + reason +
         "\r\nContent-Type: application/json; charset=utf-8\r\nContent-Length: " +
         std::to_string(body.size()) + "\r\nConnection: close\r\n" + extra_headers + "\r\n" + body;
}

ConnectionPool::ConnectionPool(int workers, int waiting)
    : most_waiting_(static_cast<std::size_t>(waiting)) {
  for (int i = 0; i < workers; ++i)
    workers_.emplace_back([this] { work(queued_); });
  refuser_ = std::thread([this] {
    refusal_thread = true;
    work(refused_);
  });
}

ConnectionPool::~ConnectionPool() {
  shutdown();
}

bool ConnectionPool::refusing_on_this_thread() {
  return refusal_thread;
}

void ConnectionPool::enqueue(std::function<void()> serve) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (queued_.size() < most_waiting_) {
      queued_.push_back(std::move(serve));
      waiting_now_ = static_cast<int>(queued_.size());
    } else {
      refused_.push_back(std::move(serve));
    }
  }
  wake_.notify_all();
}

void ConnectionPool::shutdown() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ && workers_.empty()) return;
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_)
    worker.join();
  workers_.clear();
  if (refuser_.joinable()) refuser_.join();
}

void ConnectionPool::work(std::deque<std::function<void()>>& queue) {
  for (;;) {
    std::function<void()> serve;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !queue.empty(); });
      if (queue.empty()) return;  // stopping, and nothing left to serve
      serve = std::move(queue.front());
      queue.pop_front();
      waiting_now_ = static_cast<int>(queued_.size());
    }
    serve();
  }
}

GuardedServer::GuardedServer(const ConnectionLimits& limits) : limits_(limits) {
  new_task_queue = [this] {
    auto* pool = new ConnectionPool(limits_.workers, limits_.waiting);
    pool_ = pool;
    return pool;
  };
}

bool GuardedServer::deepen_listen_queue() {
  const socket_t sock = svr_sock_;
  return sock != INVALID_SOCKET && ::listen(sock, limits_.listen_backlog) == 0;
}

bool GuardedServer::wait_for_request(socket_t sock) const {
  // A connection new or idle is closed for one waiting only after this long, so that a request
  // on its way is not cut off.
  constexpr auto kGrace = std::chrono::milliseconds(100);
  constexpr int kSliceMillis = 20;
  const Clock::time_point start = Clock::now();
  const Clock::time_point idle_end = start + std::chrono::seconds(limits_.idle_seconds);
  while (svr_sock_ != INVALID_SOCKET) {
    if (poll_for(sock, POLLIN, std::min(kSliceMillis, millis_until(idle_end)))) return true;
    const Clock::time_point now = Clock::now();
    if (now >= idle_end) return false;
    if (pool_ && pool_->has_waiting() && now - start >= kGrace) return false;
  }
  return false;
}

bool GuardedServer::process_and_close_socket(socket_t sock) {
  if (ConnectionPool::refusing_on_this_thread()) {
    send_all(sock,
             refusal_response(503, "Service Unavailable", "",
                              "the studio is serving as many connections as it can; try again",
                              "Retry-After: 1\r\n" + refusal_headers_),
             1);
    close_after_answer(sock, 50);
    return true;
  }
  BoundedStream stream(sock, limits_, refusal_headers_);
  bool served = true;
  for (std::size_t left = limits_.keep_alive_requests; left > 0; --left) {
    // Bytes read already (a request sent right behind the last) need no wait.
    if (!stream.has_buffered() && !wait_for_request(sock)) break;
    stream.begin_head();
    bool client_closes = false;
    served = process_request(stream, left == 1, client_closes,
                             [&stream](httplib::Request&) { stream.end_head(); });
    if (!served || client_closes || stream.refused()) break;
  }
  if (stream.refused()) {
    close_after_answer(sock, 100);
  } else {
    ::shutdown(sock, SHUT_RDWR);
    ::close(sock);
  }
  return served;
}

}  // namespace fuzzygait::studio::detail
