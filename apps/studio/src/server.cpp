#include "fuzzygait/studio/server.hpp"

#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "assets.hpp"

namespace fuzzygait::studio {
namespace {

using nlohmann::json;

constexpr const char* kJson = "application/json; charset=utf-8";

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

void refuse(httplib::Response& res, int status, const std::string& field,
            const std::string& message) {
  res.status = status;
  send_json(res, RequestError(status, field, message).to_json());
}

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

}  // namespace

struct Server::Impl {
  Studio& studio;
  ServerOptions options;
  httplib::Server http;
  std::mutex studio_mutex;  // one request at a time reads or changes the studio
  int port = 0;
  bool loopback = true;
  // run() and stop() may race: stop() before run() has started listening must still end it.
  std::atomic<bool> stopping{false};
  std::atomic<int> run_state{0};  // 0 not called, 1 running, 2 returned

  Impl(Studio& s, ServerOptions o) : studio(s), options(std::move(o)) {}

  // Host values a browser sends for this server on loopback (DNS rebinding gives other names).
  bool own_host(const std::string& host) const {
    const std::string p = ":" + std::to_string(port);
    return host == "127.0.0.1" + p || host == "localhost" + p || host == "[::1]" + p ||
           host == options.host + p;
  }

  // The JSON body of a POST (an empty one reads as {}); throws RequestError when malformed.
  static json body(const httplib::Request& req) {
    if (req.body.empty()) return json::object();
    try {
      return json::parse(req.body);
    } catch (const json::exception& e) {
      throw RequestError(400, "body", std::string("the body is not JSON: ") + e.what());
    }
  }

  // A route answering JSON from a Studio call made under the lock. The time the call took is
  // sent as Server-Timing (the browser test reads it).
  httplib::Server::Handler api(std::function<json(const json&)> call) {
    return [this, call = std::move(call)](const httplib::Request& req, httplib::Response& res) {
      try {
        const json request = body(req);
        json answer;
        const auto start = std::chrono::steady_clock::now();
        {
          const std::lock_guard<std::mutex> lock(studio_mutex);
          answer = call(request);
        }
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        char timing[64];
        std::snprintf(timing, sizeof timing, "studio;dur=%.2f", ms);
        res.set_header("Server-Timing", timing);
        res.set_header("Cache-Control", "no-store");
        send_json(res, answer);
      } catch (const RequestError& e) {
        res.status = e.status();
        send_json(res, e.to_json());
      } catch (const std::exception& e) {
        refuse(res, 500, "", std::string("the studio failed: ") + e.what());
      }
    };
  }

  // Host, path and POST checks before any route; Handled when refused.
  httplib::Server::HandlerResponse screen(const httplib::Request& req, httplib::Response& res) {
    using Response = httplib::Server::HandlerResponse;
    if (loopback && !own_host(req.get_header_value("Host"))) {
      refuse(res, 403, "Host",
             "this studio answers requests for 127.0.0.1:" + std::to_string(port) +
                 " or localhost:" + std::to_string(port) + " only");
      return Response::Handled;
    }
    if (req.path.find("..") != std::string::npos) {
      refuse(res, 400, "path", "'..' is not allowed in a path");
      return Response::Handled;
    }
    if (req.method == "POST") {
      const std::string origin = req.get_header_value("Origin");
      if (loopback && !origin.empty() && origin.rfind("http://", 0) == 0 &&
          !own_host(origin.substr(7))) {
        refuse(res, 403, "Origin", "requests from pages of other sites are refused");
        return Response::Handled;
      }
      if (!origin.empty() && origin.rfind("http://", 0) != 0) {
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

  void routes() {
    http.Get("/api/state", api([this](const json&) { return studio.state(); }));
    http.Get("/api/walk", api([this](const json&) { return studio.walk(); }));
    http.Post("/api/edit", api([this](const json& r) { return studio.edit(r); }));
    http.Post("/api/settings", api([this](const json& r) { return studio.change_settings(r); }));
    http.Post("/api/undo", api([this](const json&) { return studio.undo(); }));
    http.Post("/api/redo", api([this](const json&) { return studio.redo(); }));
    http.Post("/api/open", api([this](const json& r) { return studio.open(r); }));
    http.Post("/api/save", api([this](const json& r) { return studio.save(r); }));
    http.Post("/api/compare", api([this](const json& r) { return studio.compare(r); }));
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
  s.loopback = is_loopback(options.host);
  const auto threads = static_cast<std::size_t>(options.threads);
  s.http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  // SO_REUSEADDR alone (cpp-httplib's default sets SO_REUSEPORT, with which a second studio on
  // the same port would bind too and take half the connections).
  s.http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  // Small answers go out at once, not after a delayed acknowledgement.
  s.http.set_tcp_nodelay(true);
  s.http.set_payload_max_length(options.max_body);
  s.http.set_keep_alive_max_count(1000);
  s.http.set_keep_alive_timeout(5);
  s.http.set_read_timeout(5, 0);
  s.http.set_write_timeout(5, 0);
  s.http.set_pre_routing_handler(
      [&s](const httplib::Request& req, httplib::Response& res) { return s.screen(req, res); });
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
}

Server::~Server() {
  stop();
}

int Server::port() const {
  return impl_->port;
}

std::string Server::address() const {
  const std::string& host = impl_->options.host;
  const bool ipv6 = host.find(':') != std::string::npos;
  return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(impl_->port) + "/";
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
