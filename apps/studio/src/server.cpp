#include "fuzzygait/studio/server.hpp"

#include <httplib.h>
#include <openssl/evp.h>
#include <openssl/sha.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <functional>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>

#include "assets.hpp"
#include "connections.hpp"

namespace fuzzygait::studio {
namespace {

using nlohmann::json;

constexpr const char* kJson = "application/json; charset=utf-8";

// Past the body limit the server reads on and drops this many bytes more, so that its refusal
// reaches a client that is still sending (closing a socket with unread bytes resets it, and the
// client may lose the answer); beyond that it stops reading and closes the connection.
constexpr std::size_t kDrainLimit = 16 * 1024 * 1024;

// Sends bytes as they are, through a content provider: cpp-httplib would compress a body given
// with set_content of a text type (Brotli at its slowest setting), which on this machine costs
// far more than sending megabytes over loopback.
void send(httplib::Response& res, std::shared_ptr<const std::string> bytes, const char* type) {
  const std::size_t size = bytes->size();
  res.set_content_provider(
      size, type, [bytes](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        sink.write(bytes->data() + offset, std::min(length, bytes->size() - offset));
        return true;
      });
}

void send_view(httplib::Response& res, std::string_view text, std::string_view type) {
  res.set_content_provider(text.size(), std::string(type).c_str(),
                           [text](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                             sink.write(text.data() + offset,
                                        std::min(length, text.size() - offset));
                             return true;
                           });
}

// JSON text that never throws: strings that are not UTF-8 (a description in a file of one's own)
// are sent with replacement characters.
std::string dump(const json& value) {
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

void send_json(httplib::Response& res, const json& value) {
  send(res, std::make_shared<const std::string>(dump(value)), kJson);
}

// Sends the JSON and then closes the connection: a content provider that reports failure after
// writing its bytes makes cpp-httplib end the connection instead of reading the next request
// from it (for a body left half read).
void send_json_and_close(httplib::Response& res, const json& value) {
  auto bytes = std::make_shared<const std::string>(dump(value));
  res.set_header("Connection", "close");
  res.set_content_provider(
      bytes->size(), kJson,
      [bytes](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        sink.write(bytes->data() + offset, std::min(length, bytes->size() - offset));
        return false;
      });
}

void refuse(httplib::Response& res, int status, const std::string& field,
            const std::string& message) {
  res.status = status;
  send_json(res, RequestError(status, field, message).to_json());
}

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// A host as it is written in a Host header: an IPv6 address in brackets.
std::string host_in_url(const std::string& host) {
  const bool ipv6 = host.find(':') != std::string::npos && host.front() != '[';
  return ipv6 ? "[" + host + "]" : host;
}

// The page's one inline script, its import map, as a Content-Security-Policy source
// ('sha256-BASE64'), so that no other inline script runs.
std::string import_map_source() {
  const detail::Asset* page = detail::find_asset("/index.html");
  if (!page) return {};
  const std::string_view html = page->text;
  const std::string_view open = "<script type=\"importmap\">";
  const std::size_t start = html.find(open);
  const std::size_t end = html.find("</script>", start);
  if (start == std::string_view::npos || end == std::string_view::npos) return {};
  const std::string_view script = html.substr(start + open.size(), end - start - open.size());
  unsigned char digest[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>(script.data()), script.size(), digest);
  unsigned char base64[4 * ((SHA256_DIGEST_LENGTH + 2) / 3) + 1];
  EVP_EncodeBlock(base64, digest, SHA256_DIGEST_LENGTH);
  return " 'sha256-" + std::string(reinterpret_cast<const char*>(base64)) + "'";
}

// What the page may load and run: its own files and its import map; styles inline too (lil-gui
// adds its own); images and fonts (lil-gui's) from data: URLs; requests to this server only; no
// frames around it.
std::string content_security_policy() {
  return "default-src 'self'; script-src 'self'" + import_map_source() +
         "; style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:; font-src 'self' data:; "
         "connect-src 'self'; "
         "object-src 'none'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'";
}

// How reading a POST's body ended.
enum class BodyRead { kWhole, kTooLarge, kAbandoned, kBroken };

// Reads a POST's body through cpp-httplib's content reader, keeping at most `limit` bytes
// whatever the transfer encoding: cpp-httplib 0.11 checks set_payload_max_length against a
// Content-Length only, and would keep a chunked body, or one sent until the connection closes,
// whole in memory. Past the limit the bytes are read and dropped, up to kDrainLimit.
BodyRead read_body(const httplib::ContentReader& reader, const httplib::Response& res,
                   std::size_t limit, std::string& body) {
  std::size_t dropped = 0;
  const bool read = reader([&](const char* data, std::size_t size) {
    if (dropped == 0 && body.size() + size <= limit) {
      body.append(data, size);
      return true;
    }
    dropped += size;
    return dropped <= kDrainLimit;
  });
  // A Content-Length over the limit: cpp-httplib skipped the body and set 413.
  if (res.status == 413) return BodyRead::kTooLarge;
  if (dropped > kDrainLimit) return BodyRead::kAbandoned;
  if (dropped > 0) return read ? BodyRead::kTooLarge : BodyRead::kAbandoned;
  return read ? BodyRead::kWhole : BodyRead::kBroken;
}

detail::ConnectionLimits connection_limits(const ServerOptions& options) {
  detail::ConnectionLimits limits;
  limits.workers = options.threads;
  limits.waiting = options.waiting;
  limits.idle_seconds = options.idle_seconds;
  limits.head_seconds = options.idle_seconds;
  limits.listen_backlog = options.listen_backlog;
  return limits;
}

}  // namespace

struct Server::Impl {
  Studio& studio;
  ServerOptions options;
  detail::GuardedServer http;
  std::mutex studio_mutex;  // one request at a time reads or changes the studio
  int port = 0;
  bool loopback = true;
  std::set<std::string> host_names;  // what a Host header may name, without the port
  std::string security_policy = content_security_policy();
  // run() and stop() may race: stop() before run() has started listening must still end it.
  std::atomic<bool> stopping{false};
  std::atomic<int> run_state{0};  // 0 not called, 1 running, 2 returned

  Impl(Studio& s, ServerOptions o)
      : studio(s), options(std::move(o)), http(connection_limits(options)) {
    host_names = {"127.0.0.1", "localhost", "[::1]"};
    if (options.host != "0.0.0.0" && options.host != "::" && !options.host.empty())
      host_names.insert(lower(host_in_url(options.host)));
    for (const std::string& name : options.allowed_hosts)
      host_names.insert(lower(host_in_url(name)));
  }

  // Host values a browser sends for this server: a loopback name or one the server was given,
  // with its port. DNS rebinding gives another name (the attacker's), whatever address the
  // server listens on.
  bool own_host(const std::string& host) const {
    const std::string p = ":" + std::to_string(port);
    if (host.size() <= p.size() || host.compare(host.size() - p.size(), p.size(), p) != 0)
      return false;
    return host_names.count(lower(host.substr(0, host.size() - p.size()))) > 0;
  }

  std::string own_hosts_text() const {
    std::string text;
    for (const std::string& name : host_names)
      text += (text.empty() ? "" : ", ") + name + ":" + std::to_string(port);
    return text;
  }

  // The JSON body of a POST (an empty one reads as {}); throws RequestError when malformed.
  static json parse_body(const std::string& body) {
    if (body.empty()) return json::object();
    try {
      return json::parse(body);
    } catch (const json::exception& e) {
      throw RequestError(400, "body", std::string("the body is not JSON: ") + e.what());
    }
  }

  // Answers JSON from a Studio call made under the lock. The time the call took is sent as
  // Server-Timing (the browser test reads it).
  void answer(const std::function<json(const json&)>& call, const std::string& body,
              httplib::Response& res) {
    try {
      const json request = parse_body(body);
      json result;
      const auto start = std::chrono::steady_clock::now();
      {
        const std::lock_guard<std::mutex> lock(studio_mutex);
        result = call(request);
      }
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      char timing[64];
      std::snprintf(timing, sizeof timing, "studio;dur=%.2f", ms);
      res.set_header("Server-Timing", timing);
      res.set_header("Cache-Control", "no-store");
      send_json(res, result);
    } catch (const RequestError& e) {
      res.status = e.status();
      send_json(res, e.to_json());
    } catch (const std::exception& e) {
      refuse(res, 500, "", std::string("the studio failed: ") + e.what());
    }
  }

  // A GET route answering JSON from a Studio call.
  httplib::Server::Handler get(std::function<json(const json&)> call) {
    return [this, call = std::move(call)](const httplib::Request&, httplib::Response& res) {
      answer(call, "", res);
    };
  }

  // A POST route answering JSON from a Studio call with the request's body, read within the
  // limit (read_body); `call` null answers that there is no such route.
  // `largest_body` 0: options.max_body.
  httplib::Server::HandlerWithContentReader post(std::function<json(const json&)> call,
                                                 std::size_t largest_body = 0) {
    const std::size_t limit = std::max(options.max_body, largest_body);
    return
        [this, call = std::move(call), limit](const httplib::Request& req, httplib::Response& res,
                                              const httplib::ContentReader& reader) {
          std::string body;
          switch (read_body(reader, res, limit, body)) {
            case BodyRead::kWhole:
              break;
            case BodyRead::kTooLarge:
              res.status = 413;
              send_json(res, too_large(limit).to_json());
              return;
            case BodyRead::kAbandoned:
              res.status = 413;
              send_json_and_close(res, too_large(limit).to_json());
              return;
            case BodyRead::kBroken:
              res.status = 400;
              send_json_and_close(res, RequestError(400, "body",
                                                    "the body could not be read "
                                                    "(a malformed chunk?)")
                                           .to_json());
              return;
          }
          if (!call) {
            refuse(res, 404, "path", "no route for POST " + req.path);
            return;
          }
          answer(call, body, res);
        };
  }

  static RequestError too_large(std::size_t limit) {
    return RequestError(413, "body",
                        "the request body is larger than " + std::to_string(limit) + " bytes");
  }

  // Method, Host, path, Origin and POST checks before any route (and before a body is read);
  // Handled when refused.
  httplib::Server::HandlerResponse screen(const httplib::Request& req, httplib::Response& res) {
    using Response = httplib::Server::HandlerResponse;
    // Only these: cpp-httplib would read another method's body whole, with no limit.
    if (req.method != "GET" && req.method != "HEAD" && req.method != "POST") {
      refuse(res, 405, "method", "the studio answers GET and POST only, not " + req.method);
      res.set_header("Allow", "GET, HEAD, POST");
      return Response::Handled;
    }
    if (!own_host(req.get_header_value("Host"))) {
      refuse(res, 403, "Host", "this studio answers requests for " + own_hosts_text() + " only");
      return Response::Handled;
    }
    if (req.path.find("..") != std::string::npos) {
      refuse(res, 400, "path", "'..' is not allowed in a path");
      return Response::Handled;
    }
    if (req.method == "POST") {
      const std::string origin = req.get_header_value("Origin");
      if (!origin.empty() && (origin.rfind("http://", 0) != 0 || !own_host(origin.substr(7)))) {
        refuse(res, 403, "Origin", "requests from pages of other sites are refused");
        return Response::Handled;
      }
      const std::string type = req.get_header_value("Content-Type");
      if (type.rfind("application/json", 0) != 0) {
        refuse(res, 415, "Content-Type",
               "a POST's body must be JSON (Content-Type: "
               "application/json)");
        return Response::Handled;
      }
    }
    return Response::Unhandled;
  }

  // Headers on every answer, refusals included (those GuardedServer writes itself too).
  std::vector<std::pair<std::string, std::string>> protecting_headers() const {
    return {{"Content-Security-Policy", security_policy},
            {"X-Frame-Options", "DENY"},
            {"X-Content-Type-Options", "nosniff"},
            {"Referrer-Policy", "no-referrer"}};
  }
  void protect(httplib::Response& res) const {
    for (const auto& [name, value] : protecting_headers())
      res.set_header(name, value);
  }

  void routes() {
    http.Get("/api/state", get([this](const json&) { return studio.state(); }));
    http.Get("/api/walk", get([this](const json&) { return studio.walk(); }));
    http.Post("/api/edit", post([this](const json& r) { return studio.edit(r); }));
    http.Post("/api/fired", post([this](const json& r) { return studio.fired(r); }));
    // A controller's rules at their limits (Limits::kMostRules of Limits::kLongestRule) are
    // larger than other requests: their route reads up to Limits::kLargestRulesBody.
    http.Post("/api/rules", post([this](const json& r) { return studio.edit_rules(r); },
                                 Limits::kLargestRulesBody));
    http.Post("/api/term", post([this](const json& r) { return studio.edit_term(r); }));
    http.Post("/api/settings", post([this](const json& r) { return studio.change_settings(r); }));
    http.Post("/api/undo", post([this](const json&) { return studio.undo(); }));
    http.Post("/api/history", post([this](const json& r) { return studio.go_to(r); }));
    http.Post("/api/redo", post([this](const json&) { return studio.redo(); }));
    http.Post("/api/open", post([this](const json& r) { return studio.open(r); }));
    http.Post("/api/save", post([this](const json& r) { return studio.save(r); }));
    http.Post("/api/compare", post([this](const json& r) { return studio.compare(r); }));
    // Any other POST: its body read within the limit too, then a 404.
    http.Post(".*", post(nullptr));
    http.Get("/api/download/([^/]+)", [this](const httplib::Request& req, httplib::Response& res) {
      try {
        Download d;
        {
          const std::lock_guard<std::mutex> lock(studio_mutex);
          d = studio.download(req.matches[1].str());
        }
        res.set_header("Content-Disposition", "attachment; filename=\"" + d.filename + "\"");
        res.set_header("Cache-Control", "no-store");
        send(res, std::make_shared<const std::string>(std::move(d.bytes)), d.content_type.c_str());
      } catch (const RequestError& e) {
        res.status = e.status();
        send_json(res, e.to_json());
      } catch (const std::exception& e) {
        refuse(res, 500, "", std::string("the download failed: ") + e.what());
      }
    });
    http.Get(".*", [](const httplib::Request& req, httplib::Response& res) {
      const detail::Asset* asset = detail::find_asset(req.path);
      if (!asset) {
        refuse(res, 404, "path", "no page or file at '" + req.path + "'");
        return;
      }
      send_view(res, asset->text, asset->content_type);
    });
  }
};

Server::Server(Studio& studio, const ServerOptions& options)
    : impl_(std::make_unique<Impl>(studio, options)) {
  Impl& s = *impl_;
  if (options.port < 0 || options.port > 65535) {
    throw std::invalid_argument("port must be between 0 and 65535, got " +
                                std::to_string(options.port));
  }
  if (options.threads < 1 || options.threads > 256) {
    throw std::invalid_argument("threads must be between 1 and 256");
  }
  if (options.max_body < 1024 || options.max_body > 64 * 1024 * 1024) {
    throw std::invalid_argument("max_body must be between 1 KiB and 64 MiB");
  }
  if (options.idle_seconds < 1 || options.idle_seconds > 600) {
    throw std::invalid_argument("idle_seconds must be between 1 and 600");
  }
  if (options.waiting < 0 || options.waiting > 4096) {
    throw std::invalid_argument("waiting must be between 0 and 4096");
  }
  if (options.listen_backlog < 1 || options.listen_backlog > 65535) {
    throw std::invalid_argument("listen_backlog must be between 1 and 65535");
  }
  s.loopback = is_loopback(options.host);
  std::string refusal_headers;
  for (const auto& [name, value] : s.protecting_headers())
    refusal_headers += name + ": " + value + "\r\n";
  s.http.set_refusal_headers(std::move(refusal_headers));
  // SO_REUSEADDR alone (cpp-httplib's default sets SO_REUSEPORT, with which a second studio on
  // the same port would bind too and take half the connections).
  s.http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  // Small answers go out at once, not after a delayed acknowledgement.
  s.http.set_tcp_nodelay(true);
  // A Content-Length past the largest any route reads is refused unread; each route then reads
  // within its own limit (read_body).
  s.http.set_payload_max_length(std::max(options.max_body, Limits::kLargestRulesBody));
  s.http.set_keep_alive_max_count(1000);
  // A connection that sends nothing for idle_seconds is closed, so that idle or half-open
  // connections hold a thread of the pool for that long at most.
  s.http.set_keep_alive_timeout(options.idle_seconds);
  s.http.set_read_timeout(options.idle_seconds, 0);
  s.http.set_write_timeout(5, 0);
  s.http.set_pre_routing_handler(
      [&s](const httplib::Request& req, httplib::Response& res) { return s.screen(req, res); });
  s.http.set_post_routing_handler(
      [&s](const httplib::Request&, httplib::Response& res) { s.protect(res); });
  // Statuses cpp-httplib sets itself (413, a 404 for a method no route takes, 400 for a request
  // it cannot parse) get a JSON body too.
  s.http.set_error_handler(
      httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
        if (res.has_header("Content-Type")) return httplib::Server::HandlerResponse::Unhandled;
        std::string message = "refused";
        std::string field;
        if (res.status == 413) {
          message = "the request body is too large";
          field = "body";
        } else if (res.status == 404) {
          message = "no route for " + req.method + " " + req.path;
          field = "path";
        } else if (res.status == 400) {
          message = "malformed request";
        }
        res.set_content(dump(RequestError(res.status, field, message).to_json()), kJson);
        return httplib::Server::HandlerResponse::Handled;
      }));
  s.http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
        res.status = 500;
        res.set_content(dump(RequestError(500, "", "the studio failed").to_json()), kJson);
      });
  s.routes();
  if (options.port == 0) {
    s.port = s.http.bind_to_any_port(options.host);
  } else {
    s.port = s.http.bind_to_port(options.host, options.port) ? options.port : -1;
  }
  if (s.port < 0) {
    throw std::runtime_error("cannot listen on " + options.host + ":" +
                             std::to_string(options.port) +
                             " (in use by another program? try --port 0 for any free port)");
  }
  if (!s.http.deepen_listen_queue()) {
    throw std::runtime_error("cannot listen on " + options.host + ":" + std::to_string(s.port) +
                             " with a queue of " + std::to_string(options.listen_backlog));
  }
}

Server::~Server() {
  stop();
}

int Server::port() const {
  return impl_->port;
}

bool Server::loopback() const {
  return impl_->loopback;
}

std::string Server::address() const {
  const std::string& host = impl_->options.host;
  // Listening on every address, the page opens on loopback.
  const bool any = host == "0.0.0.0" || host == "::";
  return "http://" + (any ? std::string("127.0.0.1") : host_in_url(host)) + ":" +
         std::to_string(impl_->port) + "/";
}

bool Server::run() {
  Impl& s = *impl_;
  s.run_state = 1;
  bool listened = true;
  if (!s.stopping) listened = s.http.listen_after_bind();
  s.run_state = 2;
  return listened;
}

void Server::stop() {
  Impl& s = *impl_;
  s.stopping = true;
  // Once run() is past its check of `stopping`, it is about to listen: wait until it does.
  while (s.run_state == 1 && !s.http.is_running())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  s.http.stop();
}

}  // namespace fuzzygait::studio
