// `simlab lab`'s static server: started on an ephemeral port in a thread, it serves the
// lesson page, the WebAssembly engine as application/wasm, the lesson text and models,
// and answers 404 for paths that climb out of its roots.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "lab.h"

namespace simlab::apps {
namespace {

namespace fs = std::filesystem;

const fs::path kRepo = SIMLAB_SOURCE_DIR;

// Status code, Content-Type and body of one response.
struct Reply {
  int status = 0;
  std::string type;
  std::string body;
};

// Sends a raw request to 127.0.0.1:port and reads the whole answer.
Reply Fetch(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ::send(fd, request.data(), request.size(), 0);
  std::string raw;
  char buffer[65536];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) raw.append(buffer, n);
  ::close(fd);
  Reply reply;
  const size_t head_end = raw.find("\r\n\r\n");
  if (raw.size() < 12 || head_end == std::string::npos) return reply;
  reply.status = std::stoi(raw.substr(9, 3));
  const size_t type_at = raw.find("Content-Type: ");
  if (type_at < head_end) {
    reply.type = raw.substr(type_at + 14, raw.find("\r\n", type_at) - type_at - 14);
  }
  reply.body = raw.substr(head_end + 4);
  return reply;
}

Reply Get(int port, const std::string& path) {
  return Fetch(port, "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
}

// A server on a free port, serving in a background thread for one test.
class LabServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(scratch_);
    std::ofstream(scratch_ / "lesson-test.txt") << "## A lesson\nSome text.\n";
    // A fake engine binary, so the test does not need the WebAssembly build.
    std::ofstream(scratch_ / "engine.wasm") << "wasm";
    server_ = std::make_unique<LabServer>(LabSite{kRepo, scratch_ / "lesson-test.txt"}, 0);
    thread_ = std::thread([this] { server_->Serve(); });
  }
  void TearDown() override {
    server_->Stop();
    thread_.join();
    fs::remove_all(scratch_);
  }
  int port() const { return server_->port(); }

  fs::path scratch_ = fs::temp_directory_path() / ("simlab_lab_test_" + std::to_string(::getpid()));
  std::unique_ptr<LabServer> server_;
  std::thread thread_;
};

TEST_F(LabServerTest, ServesThePageOnAnEphemeralPort) {
  EXPECT_GT(port(), 0);
  const Reply page = Get(port(), "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_EQ(page.type, "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("<html"), std::string::npos);
  EXPECT_EQ(Get(port(), "/lesson/index.html").body, page.body);
  const Reply module = Get(port(), "/lesson/lesson.mjs");
  EXPECT_EQ(module.status, 200);
  EXPECT_EQ(module.type, "text/javascript; charset=utf-8");
}

TEST_F(LabServerTest, ServesTheLessonTextAndModels) {
  const Reply lesson = Get(port(), "/lesson.txt");
  EXPECT_EQ(lesson.status, 200);
  EXPECT_EQ(lesson.body, "## A lesson\nSome text.\n");
  const Reply model = Get(port(), "/models/gantry_gripper.xml");
  EXPECT_EQ(model.status, 200);
  EXPECT_EQ(model.type, "application/xml");
  const Reply files = Get(port(), "/models/gantry_gripper.xml.files.json");
  EXPECT_EQ(files.status, 200);
  EXPECT_EQ(files.body, R"({"files":["gripper.xml"],"model":"gantry_gripper.xml"})");
}

TEST_F(LabServerTest, WasmHasItsMimeType) {
  // The real build when it is there; otherwise the MIME table on a fake file.
  if (fs::exists(kRepo / "web/dist/simlab.wasm")) {
    const Reply wasm = Get(port(), "/dist/simlab.wasm");
    EXPECT_EQ(wasm.status, 200);
    EXPECT_EQ(wasm.type, "application/wasm");
    EXPECT_EQ(wasm.body.substr(0, 4), std::string("\0asm", 4));
  }
  EXPECT_EQ(LabMimeType(scratch_ / "engine.wasm"), "application/wasm");
  EXPECT_EQ(LabMimeType("x.mjs"), "text/javascript; charset=utf-8");
}

TEST_F(LabServerTest, RefusesPathsOutsideItsRoots) {
  for (const char* path : {"/../CMakeLists.txt", "/lesson/../../CMakeLists.txt",
                           "/models/../apps/lab.cc", "/models/%2e%2e/apps/lab.cc",
                           "/dist/..%2f..%2fCMakeLists.txt", "/CMakeLists.txt", "/web/lesson/index.html",
                           "/models/", "/models/nothing.xml", "/node_modules/playwright-core/index.mjs",
                           "/lesson/%00", "/models/..\\apps\\lab.cc"}) {
    const Reply reply = Get(port(), path);
    EXPECT_EQ(reply.status, 404) << path;
    EXPECT_EQ(reply.body.find("cmake_minimum_required"), std::string::npos) << path;
  }
  EXPECT_FALSE(ResolveLabPath(LabSite{kRepo, scratch_ / "lesson-test.txt"}, "/lesson/../../README.md"));
}

// An absolute file= (here an XML outside the model folder naming a file of its own) is
// neither listed nor read; relative files next to the model are.
TEST_F(LabServerTest, ModelFileListSkipsAbsoluteNames) {
  const fs::path folder = scratch_ / "model";
  fs::create_directories(folder);
  std::ofstream(scratch_ / "outside.xml") << R"(<mujoco><include file="leaked.xml"/></mujoco>)";
  std::ofstream(folder / "part.xml") << "<mujoco/>";
  std::ofstream(folder / "main.xml") << "<mujoco><include file=\"" + (scratch_ / "outside.xml").string() +
                                            "\"/><include file=\"part.xml\"/></mujoco>";
  EXPECT_EQ(LabModelFilesJson(folder / "main.xml"), R"({"files":["part.xml"],"model":"main.xml"})");
}

TEST_F(LabServerTest, AnswersOnlyGetAndHead) {
  EXPECT_EQ(Fetch(port(), "POST / HTTP/1.1\r\nHost: x\r\n\r\n").status, 405);
  EXPECT_EQ(Fetch(port(), "nonsense\r\n\r\n").status, 400);
  const Reply head = Fetch(port(), "HEAD /lesson.txt HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.body, "");
}

TEST(LabServer, PortInUseIsAClearError) {
  LabServer first({kRepo, kRepo / "README.md"}, 0);
  try {
    LabServer second({kRepo, kRepo / "README.md"}, first.port());
    FAIL() << "second server bound the same port";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace simlab::apps
