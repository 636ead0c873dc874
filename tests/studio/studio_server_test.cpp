// The studio's HTTP server as a browser and a hostile client meet it: the page and its packages as
// built, the API's JSON, refusals with a 4xx status and a JSON body naming the field, hundreds of
// malformed and concurrent requests after which it still answers, and `fuzzygait studio` serving
// until Ctrl-C.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "fuzzygait/studio/server.hpp"
#include "fuzzygait/studio/studio.hpp"
#include "scratch.hpp"
#include "support/text.hpp"

namespace fuzzygait {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

std::filesystem::path scratch(const std::string& name) {
  return test::studio_scratch("server", name);
}

studio::ServerOptions any_port() {
  studio::ServerOptions o;
  o.port = 0;
  return o;
}

// A studio served on a free loopback port for the length of a test.
class ServedStudio {
 public:
  // Listening on any free port; `serve` false leaves run() to the test.
  explicit ServedStudio(const std::string& name, bool serve = true)
      : studio_(options(name)), server_(studio_, any_port()) {
    if (serve) runner_ = std::thread([this] { server_.run(); });
  }
  ~ServedStudio() {
    server_.stop();
    if (runner_.joinable()) runner_.join();
  }
  ServedStudio(const ServedStudio&) = delete;
  ServedStudio& operator=(const ServedStudio&) = delete;
  int port() const { return server_.port(); }
  studio::Studio& studio() { return studio_; }
  studio::Server& server() { return server_; }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port());
    c.set_read_timeout(30, 0);
    return c;
  }

 private:
  static studio::StudioOptions options(const std::string& name) {
    studio::StudioOptions o;
    o.workspace = scratch(name);
    o.cycles = 3;
    return o;
  }
  studio::Studio studio_;
  studio::Server server_;
  std::thread runner_;
};

// Sends `bytes` on a new connection and reads until the server closes it or `timeout` passes.
// `half_close` ends the sending side after the bytes (for bytes that are not a whole request, so
// that the server sees their end at once; cpp-httplib drops a long answer to a half-closed
// connection, as to a closed one).
std::string raw_exchange(int port, const std::string& bytes, bool half_close = false,
                         std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return {};
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  std::string response;
  if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) break;
      sent += static_cast<std::size_t>(n);
    }
    if (half_close) shutdown(fd, SHUT_WR);
    const auto end = std::chrono::steady_clock::now() + timeout;
    char buffer[4096];
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd, POLLIN, 0};
      if (poll(&p, 1, 100) <= 0) continue;
      const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      response.append(buffer, static_cast<std::size_t>(n));
    }
  }
  close(fd);
  return response;
}

int status_of(const std::string& response) {
  if (response.rfind("HTTP/1.1 ", 0) != 0) return 0;
  return std::stoi(response.substr(9, 3));
}

json body_of(const std::string& response) {
  const std::size_t start = response.find("\r\n\r\n");
  return start == std::string::npos ? json()
                                    : json::parse(response.substr(start + 4), nullptr, false);
}

std::string request(const std::string& method, const std::string& path, int port,
                    const std::string& body = "", const std::string& headers = "") {
  std::string text = method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                     "\r\nConnection: close\r\n" + headers;
  if (method == "POST") text += "Content-Length: " + std::to_string(body.size()) + "\r\n";
  return text + "\r\n" + body;
}

std::string json_post(const std::string& path, int port, const std::string& body,
                      const std::string& headers = "") {
  return request("POST", path, port, body, "Content-Type: application/json\r\n" + headers);
}

TEST(StudioServer, ServesThePageAndThePackagesAsInstalledByNpm) {
  ServedStudio served("page");
  httplib::Client client = served.client();
  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_THAT(page->get_header_value("Content-Type"), HasSubstr("text/html"));
  EXPECT_THAT(page->body, HasSubstr("importmap"));
  const std::filesystem::path modules =
      std::filesystem::path(FUZZYGAIT_STUDIO_NPM_DIR) / "node_modules";
  for (const char* file :
       {"three/build/three.core.js", "uplot/dist/uPlot.esm.js", "lil-gui/dist/lil-gui.esm.js"}) {
    const auto served_file = client.Get(std::string("/vendor/") + file);
    ASSERT_TRUE(served_file) << file;
    EXPECT_EQ(served_file->status, 200) << file;
    EXPECT_THAT(served_file->get_header_value("Content-Type"), HasSubstr("text/javascript"));
    EXPECT_EQ(served_file->body, test::read_text(modules / file)) << file;
  }
  const auto main_module = client.Get("/src/main.js");
  ASSERT_TRUE(main_module);
  EXPECT_EQ(main_module->body,
            test::read_text(std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "studio/src/main.js"));
}

TEST(StudioServer, AnswersTheApiWithTheStudiosJson) {
  ServedStudio served("api");
  httplib::Client client = served.client();
  const auto state = client.Get("/api/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(state->status, 200);
  EXPECT_EQ(json::parse(state->body), served.studio().state());
  const auto edit = client.Post(
      "/api/edit",
      R"({"controller": "swing_knee", "variable": "velocity", "term": "hold", "value": 30})",
      "application/json");
  ASSERT_TRUE(edit);
  EXPECT_EQ(edit->status, 200);
  EXPECT_EQ(json::parse(edit->body).at("history").at("undo"), 1);
  EXPECT_THAT(edit->get_header_value("Server-Timing"), HasSubstr("studio;dur="));
  const auto glb = client.Get("/api/download/walk.glb");
  ASSERT_TRUE(glb);
  EXPECT_EQ(glb->status, 200);
  EXPECT_EQ(glb->body.substr(0, 4), "glTF");
  EXPECT_EQ(glb->get_header_value("Content-Disposition"), "attachment; filename=\"walk.glb\"");
  const auto undo = client.Post("/api/undo", "{}", "application/json");
  ASSERT_TRUE(undo);
  EXPECT_EQ(json::parse(undo->body).at("history").at("redo"), 1);
}

TEST(StudioServer, RefusesWithAStatusAndJsonNamingTheField) {
  ServedStudio served("refusals");
  const int port = served.port();
  struct Case {
    const char* what;
    std::string bytes;
    int status;
    const char* field;
  };
  const std::vector<Case> cases = {
      {"a path out of the page", request("GET", "/../../etc/passwd", port), 400, "path"},
      {"an encoded path out of the page", request("GET", "/vendor/%2e%2e/%2e%2e/etc/passwd", port),
       400, "path"},
      {"a page that is not there", request("GET", "/secret.txt", port), 404, "path"},
      {"another site's host name (DNS rebinding)",
       "GET /api/state HTTP/1.1\r\nHost: attacker.example:" + std::to_string(port) +
           "\r\nConnection: close\r\n\r\n",
       403, "Host"},
      {"another site's page",
       json_post("/api/undo", port, "{}", "Origin: http://attacker.example\r\n"), 403, "Origin"},
      {"a form post",
       request("POST", "/api/edit", port, "controller=swing_knee",
               "Content-Type: application/x-www-form-urlencoded\r\n"),
       415, "Content-Type"},
      {"a body over the limit", json_post("/api/edit", port, std::string(100 * 1024, ' ')), 413,
       "body"},
      {"malformed JSON", json_post("/api/edit", port, "{\"controller\": "), 400, "body"},
      {"NaN", json_post("/api/edit", port, R"({"controller": "swing_knee", "value": NaN})"), 400,
       "body"},
      {"a number past a double", json_post("/api/settings", port, R"({"step": 1e999})"), 400,
       "body"},
      {"a step the legs cannot reach", json_post("/api/settings", port, R"({"step": 2.5})"), 422,
       "step"},
      {"a knot past its neighbour",
       json_post("/api/edit", port,
                 R"({"controller": "swing_knee", "variable": "delta", "knot": 1, "value": 9})"),
       422, "value"},
      {"deep nesting",
       json_post("/api/edit", port, std::string(30000, '[') + std::string(30000, ']')), 400,
       "body"},
      {"an unknown download", request("GET", "/api/download/passwd", port), 404, "file"},
  };
  for (const Case& c : cases) {
    const std::string response = raw_exchange(port, c.bytes);
    EXPECT_EQ(status_of(response), c.status) << c.what << "\n" << response.substr(0, 300);
    const json body = body_of(response);
    ASSERT_TRUE(body.is_object()) << c.what << "\n" << response.substr(0, 300);
    EXPECT_EQ(body.value("field", "?"), c.field) << c.what;
    EXPECT_FALSE(body.value("error", "").empty()) << c.what;
    EXPECT_EQ(response.find("root:"), std::string::npos) << c.what;
  }
  EXPECT_EQ(served.studio().state().at("history").at("undo"), 0);
}

// Hundreds of requests from eight clients at once, most of them malformed or hostile, some of
// them edits: every one is answered (or its connection closed for bytes that are not HTTP), and
// afterwards the server answers, with exactly the accepted edits in its history.
TEST(StudioServer, StaysUpUnderHundredsOfMalformedAndConcurrentRequests) {
  ServedStudio served("stress");
  const int port = served.port();
  constexpr int kClients = 8;
  constexpr int kRequestsEach = 40;
  std::atomic<int> edits_accepted{0};
  std::atomic<int> answered{0};
  std::atomic<int> server_errors{0};
  std::atomic<int> unanswered_http{0};
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      std::mt19937 random(static_cast<unsigned>(1000 + c));
      for (int i = 0; i < kRequestsEach; ++i) {
        std::string bytes;
        bool http = true;
        bool edit = false;
        switch (random() % 12) {
          case 0: {  // random bytes, not HTTP at all
            bytes.resize(1 + random() % 2000);
            for (char& b : bytes)
              b = static_cast<char>(random() % 256);
            http = false;
            break;
          }
          case 1:  // a request line cut short
            bytes = "GET /api/sta";
            http = false;
            break;
          case 2:  // a header line of 20 KB
            bytes = "GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                    "\r\nX-Long: " + std::string(20000, 'x') + "\r\n\r\n";
            http = false;
            break;
          case 3:
            bytes = json_post("/api/edit", port,
                              "{\"controller\": [" + std::string(random() % 50, '{'));
            break;
          case 4:
            bytes = json_post(
                "/api/edit", port,
                R"({"controller": "swing_knee", "variable": "delta", "knot": -1, "value": 0})");
            break;
          case 5:
            bytes = json_post("/api/settings", port, R"({"stature": "tall"})");
            break;
          case 6:
            bytes = request("GET", "/..%2f..%2fetc/passwd", port);
            break;
          case 7:
            bytes = json_post("/api/open", port, R"({"set": "saved:../../../etc"})");
            break;
          case 8:
            bytes = request("DELETE", "/api/state", port);
            break;
          case 9:
            bytes = json_post("/api/save", port, R"({"name": "/tmp/x"})");
            break;
          case 10:
            bytes = request("GET", "/api/state", port);
            break;
          default: {  // an edit the studio takes
            const double value = 20.0 + static_cast<double>(random() % 40);
            bytes = json_post(
                "/api/edit", port,
                R"({"controller": "swing_knee", "variable": "velocity", "term": "hold", "value": )" +
                    std::to_string(value) + "}");
            edit = true;
            break;
          }
        }
        const std::string response = raw_exchange(port, bytes, !http);
        const int status = status_of(response);
        if (status != 0) ++answered;
        if (status >= 500) ++server_errors;
        if (http && status == 0) ++unanswered_http;
        if (edit && status == 200) ++edits_accepted;
      }
    });
  }
  for (std::thread& t : clients)
    t.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%d requests from %d clients in %.2f s, %d answered, %d edits accepted\n",
              kClients * kRequestsEach, kClients, seconds, answered.load(), edits_accepted.load());
  EXPECT_EQ(server_errors, 0);
  EXPECT_EQ(unanswered_http, 0);
  EXPECT_GT(edits_accepted, 0);
  httplib::Client client = served.client();
  const auto state = client.Get("/api/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(state->status, 200);
  EXPECT_EQ(json::parse(state->body).at("history").at("undo").get<int>(), edits_accepted.load());
  EXPECT_FALSE(std::filesystem::exists("/tmp/x/manifest.json"));
}

TEST(StudioServer, ListensOnLoopbackByDefault) {
  EXPECT_EQ(studio::ServerOptions{}.host, "127.0.0.1");
  ServedStudio served("loopback");
  EXPECT_EQ(served.server().address(), "http://127.0.0.1:" + std::to_string(served.port()) + "/");
  // A port in use is refused naming the address.
  studio::ServerOptions taken;
  taken.port = served.port();
  try {
    studio::Server second(served.studio(), taken);
    FAIL() << "a second server took the same port";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("127.0.0.1:" + std::to_string(served.port())));
  }
}

TEST(StudioServer, StopEndsARunThatHasNotStartedYet) {
  ServedStudio served("stop_early", false);
  served.server().stop();
  EXPECT_TRUE(served.server().run());
}

// `fuzzygait studio` as a person starts it: it prints the address, serves, and stops on Ctrl-C.
TEST(StudioCommand, PrintsItsAddressServesAndStopsOnCtrlC) {
  int output[2];
  ASSERT_EQ(pipe(output), 0);
  const std::filesystem::path workspace = scratch("command");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    dup2(output[1], STDOUT_FILENO);
    dup2(output[1], STDERR_FILENO);
    close(output[0]);
    execl(FUZZYGAIT_CLI, FUZZYGAIT_CLI, "studio", "--port", "0", "--style", "heavy", "--workspace",
          workspace.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(output[1]);
  std::string printed;
  char buffer[256];
  while (printed.find('\n') == std::string::npos) {
    pollfd p{output[0], POLLIN, 0};
    if (poll(&p, 1, 30000) <= 0) break;
    const ssize_t n = read(output[0], buffer, sizeof buffer);
    if (n <= 0) break;
    printed.append(buffer, static_cast<std::size_t>(n));
  }
  const std::string prefix = "fuzzygait studio: open http://127.0.0.1:";
  ASSERT_EQ(printed.rfind(prefix, 0), 0u) << printed;
  const int port = std::stoi(printed.substr(prefix.size()));
  httplib::Client client("127.0.0.1", port);
  const auto state = client.Get("/api/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(json::parse(state->body).at("set").at("name"), "heavy");
  kill(child, SIGINT);
  int status = 0;
  bool exited = false;
  for (int i = 0; i < 200 && !exited; ++i) {
    exited = waitpid(child, &status, WNOHANG) == child;
    if (!exited) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (!exited) {
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    FAIL() << "fuzzygait studio did not stop on SIGINT";
  }
  while (const ssize_t n = read(output[0], buffer, sizeof buffer)) {
    if (n < 0) break;
    printed.append(buffer, static_cast<std::size_t>(n));
  }
  close(output[0]);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << printed;
  EXPECT_THAT(printed, HasSubstr("fuzzygait studio: stopped"));
}

}  // namespace
}  // namespace fuzzygait
