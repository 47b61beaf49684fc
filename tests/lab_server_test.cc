// `simlab lab`'s static server: started on an ephemeral port in a thread, it serves the
// lesson page, the WebAssembly engine as application/wasm, the lesson text and models,
// and answers 404 for paths that climb out of its roots. It answers only requests whose
// Host names it (421 otherwise), cuts off slow request heads (408), answers 503 beyond its
// connection cap, streams large files intact and answers 500 for unreadable ones. It
// survives a lesson file name that is not UTF-8 and running out of file descriptors. As
// `simlab view` it serves the viewer and the model's folder.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "lab.h"

namespace simlab::apps {
namespace {

namespace fs = std::filesystem;

const fs::path kRepo = SIMLAB_SOURCE_DIR;

using namespace std::chrono_literals;

// Status code, Content-Type, Content-Length (-1 when absent) and body of one response.
struct Reply {
  int status = 0;
  std::string type;
  long long length = -1;
  std::string body;
};

// The Host value the server accepts.
std::string HostOf(int port) { return "127.0.0.1:" + std::to_string(port); }

// A client socket whose reads give up after 5 s, so a server that never answers fails
// the test instead of hanging it.
int ClientSocket() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  const timeval timeout{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  return fd;
}

// Connects a client socket to 127.0.0.1:port.
void ConnectTo(int fd, int port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
}

// A client socket connected to 127.0.0.1:port.
int Connect(int port) {
  const int fd = ClientSocket();
  ConnectTo(fd, port);
  return fd;
}

// Everything the server sends until it closes.
std::string ReadAll(int fd) {
  std::string raw;
  char buffer[65536];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) raw.append(buffer, n);
  return raw;
}

// The value of header `name` ("Content-Type: ") in a response head, or empty.
std::string HeaderValue(const std::string& raw, size_t head_end, const std::string& name) {
  const size_t at = raw.find(name);
  if (at >= head_end) return "";
  return raw.substr(at + name.size(), raw.find("\r\n", at) - at - name.size());
}

// Splits a raw answer into its parts.
Reply ParseReply(const std::string& raw) {
  Reply reply;
  const size_t head_end = raw.find("\r\n\r\n");
  if (raw.size() < 12 || head_end == std::string::npos) return reply;
  reply.status = std::stoi(raw.substr(9, 3));
  reply.type = HeaderValue(raw, head_end, "Content-Type: ");
  const std::string length = HeaderValue(raw, head_end, "Content-Length: ");
  if (!length.empty()) reply.length = std::stoll(length);
  reply.body = raw.substr(head_end + 4);
  return reply;
}

// Sends a raw request to 127.0.0.1:port and reads the whole answer.
Reply Fetch(int port, const std::string& request) {
  const int fd = Connect(port);
  ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  const std::string raw = ReadAll(fd);
  ::close(fd);
  return ParseReply(raw);
}

Reply Get(int port, const std::string& path) {
  return Fetch(port, "GET " + path + " HTTP/1.1\r\nHost: " + HostOf(port) + "\r\n\r\n");
}

Reply Head(int port, const std::string& path) {
  return Fetch(port, "HEAD " + path + " HTTP/1.1\r\nHost: " + HostOf(port) + "\r\n\r\n");
}

// A file's bytes.
std::string ReadBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A server on a free port, serving in a background thread until destroyed.
class RunningServer {
 public:
  explicit RunningServer(LabSite site, LabLimits limits = {})
      : server_(std::move(site), 0, limits), thread_([this] { server_.Serve(); }) {}
  ~RunningServer() {
    server_.Stop();
    thread_.join();
  }
  int port() const { return server_.port(); }

 private:
  LabServer server_;
  std::thread thread_;
};

// A server on the repository for each test, and a scratch folder for its files.
class LabServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(scratch_);
    std::ofstream(lesson()) << "## A lesson\nSome text.\n";
    // A fake engine binary, so the test does not need the WebAssembly build.
    std::ofstream(scratch_ / "engine.wasm") << "wasm";
    server_ = std::make_unique<RunningServer>(LabSite{kRepo, lesson()});
  }
  void TearDown() override {
    server_.reset();
    fs::remove_all(scratch_);
  }
  int port() const { return server_->port(); }
  fs::path lesson() const { return scratch_ / "lesson-test.txt"; }

  // A repository of our own (a page and an empty models/) for files made by a test.
  fs::path MakeSiteRoot() const {
    const fs::path root = scratch_ / "site";
    fs::create_directories(root / "web/lesson");
    fs::create_directories(root / "models");
    std::ofstream(root / "web/lesson/index.html") << "<html></html>";
    return root;
  }

  fs::path scratch_ = fs::temp_directory_path() / ("simlab_lab_test_" + std::to_string(::getpid()));
  std::unique_ptr<RunningServer> server_;
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
  // The lesson's programs, which its page shows and links to.
  const Reply program = Get(port(), "/examples/l2_3_actuators.py");
  EXPECT_EQ(program.status, 200);
  EXPECT_NE(program.body.find("def force_laws"), std::string::npos);
  // The old file-list endpoint is gone (the lab's loader finds included files itself).
  EXPECT_EQ(Get(port(), "/models/gantry_gripper.xml.files.json").status, 404);
}

TEST_F(LabServerTest, WasmHasItsMimeType) {
  // The real build when it is there; otherwise the MIME table on a fake file.
  if (fs::exists(kRepo / "web/dist/simlab.wasm")) {
    const Reply wasm = Get(port(), "/dist/simlab.wasm");
    EXPECT_EQ(wasm.status, 200);
    EXPECT_EQ(wasm.type, "application/wasm");
    EXPECT_EQ(wasm.body.substr(0, 4), std::string("\0asm", 4));
    EXPECT_TRUE(wasm.body == ReadBytes(kRepo / "web/dist/simlab.wasm"));
  }
  EXPECT_EQ(LabMimeType(scratch_ / "engine.wasm"), "application/wasm");
  EXPECT_EQ(LabMimeType("x.mjs"), "text/javascript; charset=utf-8");
  EXPECT_EQ(LabMimeType("KaTeX_Main-Regular.woff2"), "font/woff2");
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

TEST_F(LabServerTest, AnswersOnlyGetAndHead) {
  EXPECT_EQ(Fetch(port(), "POST / HTTP/1.1\r\nHost: " + HostOf(port()) + "\r\n\r\n").status, 405);
  EXPECT_EQ(Fetch(port(), "nonsense\r\n\r\n").status, 400);
  // HEAD: the headers a GET would send (Content-Length included), no body.
  const Reply head = Head(port(), "/lesson.txt");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.type, "text/plain; charset=utf-8");
  EXPECT_EQ(head.length, 23);
  EXPECT_EQ(head.body, "");
  const Reply lesson_json = Head(port(), "/lesson.json");
  EXPECT_EQ(lesson_json.status, 200);
  EXPECT_GT(lesson_json.length, 0);
  EXPECT_EQ(lesson_json.body, "");
}

// DNS-rebinding defence: only a Host naming this server (any case) is answered.
TEST_F(LabServerTest, AnswersOnlyItsOwnHost) {
  const std::string own_port = std::to_string(port());
  const std::vector<std::string> own = {"127.0.0.1:" + own_port, "LocalHost:" + own_port,
                                        "[::1]:" + own_port};
  for (const std::string& host : own) {
    const std::string request = "GET /lesson.txt HTTP/1.1\r\nhOsT:  " + host + " \r\n\r\n";
    EXPECT_EQ(Fetch(port(), request).status, 200) << host;
  }
  const std::string other_port = std::to_string(port() == 65535 ? 1 : port() + 1);
  const std::vector<std::string> foreign = {"evil.example:" + own_port, "evil.example", "127.0.0.1",
                                            "127.0.0.1:" + other_port,
                                            "localhost.evil.example:" + own_port, ""};
  for (const std::string& host : foreign) {
    const Reply reply = Fetch(port(), "GET /lesson.txt HTTP/1.1\r\nHost: " + host + "\r\n\r\n");
    EXPECT_EQ(reply.status, 421) << host;
    EXPECT_NE(reply.body.find("is not this server"), std::string::npos) << host;
    EXPECT_EQ(reply.body.find("Some text"), std::string::npos) << host;
  }
}

// A request without Host (HTTP/1.0 too) or with two of them is refused the same way.
TEST_F(LabServerTest, RefusesMissingOrRepeatedHost) {
  for (const char* version : {"HTTP/1.1", "HTTP/1.0"}) {
    const Reply reply = Fetch(port(), std::string("GET /lesson.txt ") + version + "\r\n\r\n");
    EXPECT_EQ(reply.status, 421) << version;
    EXPECT_EQ(reply.type, "text/plain; charset=utf-8");
    EXPECT_NE(reply.body.find("no Host header"), std::string::npos) << reply.body;
  }
  const Reply twice = Fetch(port(), "GET /lesson.txt HTTP/1.1\r\nHost: " + HostOf(port()) +
                                        "\r\nHost: evil.example\r\n\r\n");
  EXPECT_EQ(twice.status, 421);
  EXPECT_NE(twice.body.find("more than one Host"), std::string::npos) << twice.body;
}

// True when `fd` has something to read (or has been closed) within `wait`.
bool Readable(int fd, std::chrono::milliseconds wait) {
  pollfd watch{fd, POLLIN, 0};
  return ::poll(&watch, 1, static_cast<int>(wait.count())) > 0;
}

// A slow-loris head (one byte every 50 ms, well inside any per-read timeout) is cut off
// once the whole-head deadline (300 ms here) has passed.
TEST_F(LabServerTest, SlowRequestHeadIsCutOffByTheDeadline) {
  RunningServer slow(LabSite{kRepo, lesson()}, LabLimits{300ms, 64});
  const std::string request = "GET /lesson.txt HTTP/1.1\r\nHost: " + HostOf(slow.port()) + "\r\n\r\n";
  const int fd = Connect(slow.port());
  const auto start = std::chrono::steady_clock::now();
  size_t sent = 0;
  while (sent < request.size() && !Readable(fd, 50ms)) {
    ::send(fd, &request[sent++], 1, MSG_NOSIGNAL);
  }
  const std::string raw = ReadAll(fd);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  ::close(fd);
  EXPECT_LT(sent, request.size());
  EXPECT_EQ(raw.substr(0, 12), "HTTP/1.1 408") << raw;
  EXPECT_GE(elapsed, 250ms);
  EXPECT_LT(elapsed, 2s);
}

// Asks for the lesson until it is served (slots come back as threads leave); false
// after about 2 s.
bool EventuallyServed(int port) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    if (Get(port, "/lesson.txt").status == 200) return true;
    std::this_thread::sleep_for(20ms);
  }
  return false;
}

// With every slot held by an idle connection, one more is answered 503 at once; once the
// idle ones hang up, requests are served again.
TEST_F(LabServerTest, ConnectionsBeyondTheCapAreAnswered503) {
  constexpr int kCap = 4;
  RunningServer capped(LabSite{kRepo, lesson()}, LabLimits{20s, kCap});
  std::vector<int> idle;
  for (int i = 0; i < kCap; ++i) idle.push_back(Connect(capped.port()));
  const int extra = Connect(capped.port());
  const Reply refused = ParseReply(ReadAll(extra));  // sent nothing: the answer comes anyway
  ::close(extra);
  EXPECT_EQ(refused.status, 503);
  EXPECT_NE(refused.body.find("too many open connections"), std::string::npos) << refused.body;
  for (const int fd : idle) ::close(fd);
  EXPECT_TRUE(EventuallyServed(capped.port()));
}

// A file of several chunks (3 MiB and a bit, random bytes) arrives whole, with its size
// as Content-Length; HEAD gives the same length and no bytes.
TEST_F(LabServerTest, LargeFilesStreamIntact) {
  const fs::path root = MakeSiteRoot();
  std::string bytes(3 * 1024 * 1024 + 123, '\0');
  std::mt19937 random(7);
  for (char& c : bytes) c = static_cast<char>(random());
  std::ofstream(root / "models/big.bin", std::ios::binary) << bytes;
  RunningServer site(LabSite{root, lesson()});
  const Reply reply = Get(site.port(), "/models/big.bin");
  EXPECT_EQ(reply.status, 200);
  EXPECT_EQ(reply.type, "application/octet-stream");
  EXPECT_EQ(reply.length, static_cast<long long>(bytes.size()));
  EXPECT_EQ(reply.body.size(), bytes.size());
  EXPECT_TRUE(reply.body == bytes);
  const Reply head = Head(site.port(), "/models/big.bin");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.length, static_cast<long long>(bytes.size()));
  EXPECT_EQ(head.body, "");
}

// A file that is there but cannot be opened answers 500, not an empty 200.
TEST_F(LabServerTest, UnreadableFileAnswers500) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads a file whatever its mode";
  const fs::path root = MakeSiteRoot();
  std::ofstream(root / "models/secret.xml") << "<mujoco/>";
  fs::permissions(root / "models/secret.xml", fs::perms::none);
  RunningServer site(LabSite{root, lesson()});
  const Reply reply = Get(site.port(), "/models/secret.xml");
  EXPECT_EQ(reply.status, 500);
  EXPECT_NE(reply.body.find("cannot read secret.xml"), std::string::npos) << reply.body;
  EXPECT_EQ(Get(site.port(), "/").status, 200);
}

// A lesson whose file name is not UTF-8 is still named in /lesson.json (its bad bytes
// as U+FFFD) and served; the server lives on.
TEST_F(LabServerTest, LessonNameThatIsNotUtf8IsServed) {
  const fs::path odd = scratch_ / "lesson-\xff\xfe.txt";
  std::ofstream(odd) << "odd name\n";
  RunningServer site(LabSite{kRepo, odd});
  const Reply about = Get(site.port(), "/lesson.json");
  EXPECT_EQ(about.status, 200);
  EXPECT_EQ(about.type, "application/json");
  EXPECT_EQ(about.body, "{\"file\":\"lesson-\xef\xbf\xbd\xef\xbf\xbd.txt\"}");
  EXPECT_EQ(Head(site.port(), "/lesson.json").length, static_cast<long long>(about.body.size()));
  EXPECT_EQ(Get(site.port(), "/lesson.txt").body, "odd name\n");
  EXPECT_EQ(Get(site.port(), "/").status, 200);
}

// `simlab view`'s site: the viewer page at /, the model's name at /view.json, the
// model's own folder (its meshes too) under /model/ and nothing above it; the lesson's
// paths are not served.
TEST_F(LabServerTest, ViewerServesTheModelFolder) {
  const fs::path folder = scratch_ / "robot";
  fs::create_directories(folder / "meshes");
  std::ofstream(folder / "arm.xml") << "<mujoco/>";
  std::ofstream(folder / "meshes/a.stl") << "solid a";
  std::ofstream(scratch_ / "secret.txt") << "secret";
  RunningServer site(LabSite{kRepo, {}, folder / "arm.xml"});
  const Reply page = Get(site.port(), "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("/view/view.mjs"), std::string::npos);
  EXPECT_EQ(Get(site.port(), "/view/view.mjs").status, 200);
  EXPECT_EQ(Get(site.port(), "/view.json").body, "{\"file\":\"arm.xml\"}");
  EXPECT_EQ(Get(site.port(), "/model/arm.xml").body, "<mujoco/>");
  EXPECT_EQ(Get(site.port(), "/model/meshes/a.stl").body, "solid a");
  for (const char* path : {"/model/../secret.txt", "/model/%2e%2e/secret.txt", "/lesson.txt", "/model/"}) {
    EXPECT_EQ(Get(site.port(), path).status, 404) << path;
  }
}

// Without the WebAssembly build the page cannot run: the commands say how to build it.
TEST_F(LabServerTest, MissingEngineSaysHowToBuildIt) {
  const std::string problem = MissingEngineProblem(MakeSiteRoot());
  EXPECT_NE(problem.find("not built"), std::string::npos) << problem;
  EXPECT_NE(problem.find("bash tools/build_wasm.sh"), std::string::npos) << problem;
  if (fs::exists(kRepo / "web/dist/simlab.wasm")) EXPECT_EQ(MissingEngineProblem(kRepo), "");
}

// The number one past the highest open file descriptor of this process.
int DescriptorsInUse() {
  int highest = 2;
  for (const auto& entry : fs::directory_iterator("/proc/self/fd")) {
    highest = std::max(highest, std::stoi(entry.path().filename().string()));
  }
  return highest + 1;
}

// How many file descriptors this process has open.
int OpenDescriptors() {
  int count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator("/proc/self/fd")) ++count;
  return count;
}

// Waits (up to 5 s) until this process has no more than `count` descriptors open: the
// server closes a finished connection on its own thread, a moment after the client has
// its reply.
bool SettlesAt(int count) {
  for (int tries = 0; tries < 500; ++tries) {
    if (OpenDescriptors() <= count) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

// While alive, this process has no free file descriptor: RLIMIT_NOFILE lowered a little
// above those in use and every free one below it taken by /dev/null (as idle connections
// would take them). The destructor gives them back and restores the limit.
class DescriptorExhaustion {
 public:
  DescriptorExhaustion() {
    ::getrlimit(RLIMIT_NOFILE, &saved_);
    rlimit low = saved_;
    low.rlim_cur = std::min<rlim_t>(saved_.rlim_cur, DescriptorsInUse() + 16);
    ::setrlimit(RLIMIT_NOFILE, &low);
    for (int fd; (fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;) fillers_.push_back(fd);
    full_ = errno == EMFILE;
  }
  ~DescriptorExhaustion() {
    for (const int fd : fillers_) ::close(fd);
    ::setrlimit(RLIMIT_NOFILE, &saved_);
  }
  DescriptorExhaustion(const DescriptorExhaustion&) = delete;
  DescriptorExhaustion& operator=(const DescriptorExhaustion&) = delete;
  bool full() const { return full_; }

 private:
  rlimit saved_{};
  std::vector<int> fillers_;
  bool full_ = false;
};

// accept() failing with EMFILE (no descriptor left) makes the server back off and try
// again, not stop: a connection made while the process is out of descriptors waits in
// the queue and is answered once some come back.
TEST_F(LabServerTest, KeepsAcceptingAfterRunningOutOfDescriptors) {
  RunningServer site(LabSite{kRepo, lesson()});
  const int idle = OpenDescriptors();
  ASSERT_EQ(Get(site.port(), "/lesson.json").status, 200);  // now waiting in accept()
  // The server has closed that connection: no descriptor comes free during the test.
  ASSERT_TRUE(SettlesAt(idle));
  const int first = ClientSocket();
  const int second = ClientSocket();
  const std::string request = "GET /lesson.json HTTP/1.1\r\nHost: " + HostOf(site.port()) +
                              "\r\n\r\n";
  {
    DescriptorExhaustion exhausted;
    ASSERT_TRUE(exhausted.full());
    // The first connection takes the descriptor the waiting accept() had; the next
    // accept() finds none, so the second connection cannot be taken in.
    ConnectTo(first, site.port());
    std::this_thread::sleep_for(100ms);
    ConnectTo(second, site.port());
    ::send(second, request.data(), request.size(), MSG_NOSIGNAL);
    EXPECT_FALSE(Readable(second, 300ms));
  }
  // Descriptors are back: both connections are answered, and new ones too.
  ::send(first, request.data(), request.size(), MSG_NOSIGNAL);
  EXPECT_EQ(ParseReply(ReadAll(first)).status, 200);
  EXPECT_EQ(ParseReply(ReadAll(second)).status, 200);
  ::close(first);
  ::close(second);
  EXPECT_EQ(Get(site.port(), "/lesson.txt").status, 200);
}

// Running out of descriptors or memory backs off; a failed queued connection or a
// signal retries at once; only a listening socket that is gone ends the loop.
TEST(LabServer, AcceptErrorsBackOffOrRetry) {
  for (const int error : {EMFILE, ENFILE, ENOBUFS, ENOMEM}) {
    EXPECT_EQ(LabAcceptErrorAction(error), LabAcceptAction::kBackOff) << error;
  }
  for (const int error : {EINTR, ECONNABORTED, EAGAIN, EPROTO, ENETDOWN, EHOSTUNREACH, EPERM}) {
    EXPECT_EQ(LabAcceptErrorAction(error), LabAcceptAction::kRetry) << error;
  }
  for (const int error : {EBADF, EINVAL, ENOTSOCK}) {
    EXPECT_EQ(LabAcceptErrorAction(error), LabAcceptAction::kStop) << error;
  }
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

TEST(LabServer, LimitsMustBePositive) {
  EXPECT_THROW(LabServer({kRepo, kRepo / "README.md"}, 0, LabLimits{std::chrono::milliseconds(0), 4}),
               std::exception);
  EXPECT_THROW(LabServer({kRepo, kRepo / "README.md"}, 0, LabLimits{std::chrono::seconds(1), 0}),
               std::exception);
}

}  // namespace
}  // namespace simlab::apps
