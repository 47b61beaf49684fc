#include "lab.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "simlab/simlab.h"

namespace fs = std::filesystem;

namespace simlab::apps {
namespace {

// URL prefixes and the folders (relative to the repository) they map to.
struct Mount {
  const char* prefix;
  const char* folder;
};
constexpr Mount kMounts[] = {
    {"/lesson/", "web/lesson"},
    {"/lab/", "web/lab"},
    {"/view/", "web/view"},
    {"/dist/", "web/dist"},
    {"/node_modules/three/", "web/node_modules/three"},
    {"/node_modules/uplot/", "web/node_modules/uplot"},
    {"/node_modules/katex/", "web/node_modules/katex"},
    {"/models/", "models"},
    {"/examples/", "examples"},
};

// Largest request head we read; anything longer is refused.
constexpr size_t kMaxRequestHead = 16384;
// Files go out in pieces of this size, never whole in memory.
constexpr size_t kStreamChunk = 64 * 1024;
// A peer that stops reading an answer for this long is dropped (frees its slot).
constexpr time_t kSendTimeoutSeconds = 30;
// How long the accept loop waits when the system is out of descriptors or memory.
constexpr std::chrono::milliseconds kAcceptBackOff{50};

using Clock = std::chrono::steady_clock;

// What every connection's thread needs: the site, the port Host must name, the limits.
struct ServeContext {
  LabSite site;
  int port = 0;
  LabLimits limits;
};

// Decodes %XX escapes; nothing when an escape is malformed or decodes to NUL.
std::optional<std::string> PercentDecode(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 2 >= text.size() || !std::isxdigit(static_cast<unsigned char>(text[i + 1])) ||
        !std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      return std::nullopt;
    }
    const char hex[3] = {text[i + 1], text[i + 2], 0};
    const char c = static_cast<char>(std::strtol(hex, nullptr, 16));
    if (c == 0) return std::nullopt;
    out += c;
    i += 2;
  }
  return out;
}

// True when a path's segments include "..", or it holds a backslash.
bool ClimbsOut(const std::string& path) {
  if (path.find('\\') != std::string::npos) return true;
  std::stringstream segments(path);
  std::string segment;
  while (std::getline(segments, segment, '/')) {
    if (segment == "..") return true;
  }
  return false;
}

// `file` if it exists as a regular file inside `root` (after resolving links).
std::optional<fs::path> InsideRoot(const fs::path& root, const fs::path& file) {
  std::error_code ec;
  const fs::path real_root = fs::weakly_canonical(root, ec);
  if (ec) return std::nullopt;
  const fs::path real_file = fs::weakly_canonical(file, ec);
  if (ec || !fs::is_regular_file(real_file, ec)) return std::nullopt;
  const std::string r = real_root.string() + "/";
  if (real_file.string().compare(0, r.size(), r) != 0) return std::nullopt;
  return real_file;
}

// The url path without its query or fragment, decoded; nothing when malformed.
std::optional<std::string> CleanUrlPath(const std::string& url_path) {
  const std::string bare = url_path.substr(0, url_path.find_first_of("?#"));
  auto decoded = PercentDecode(bare);
  if (!decoded || decoded->empty() || (*decoded)[0] != '/' || ClimbsOut(*decoded)) {
    return std::nullopt;
  }
  return decoded;
}

// The status line and the headers every answer carries, for a body of `length` bytes.
std::string ResponseHead(int status, const std::string& reason, const std::string& type,
                         uintmax_t length) {
  std::ostringstream out;
  out << "HTTP/1.1 " << status << " " << reason << "\r\n"
      << "Content-Type: " << type << "\r\n"
      << "Content-Length: " << length << "\r\n"
      << "Cache-Control: no-store\r\n"
      << "X-Content-Type-Options: nosniff\r\n"
      << "Connection: close\r\n\r\n";
  return out.str();
}

// A whole answer held in memory: the headers, then the body unless only headers are wanted.
std::string TextResponse(int status, const std::string& reason, const std::string& type,
                         const std::string& body, bool head_only) {
  const std::string head = ResponseHead(status, reason, type, body.size());
  return head_only ? head : head + body;
}

// A plain-text error answer whose body says why.
std::string ErrorResponse(int status, const std::string& reason, const std::string& detail,
                          bool head_only = false) {
  return TextResponse(status, reason, "text/plain; charset=utf-8",
                      std::to_string(status) + " " + reason + ": " + detail + "\n", head_only);
}

// Sends all of `size` bytes; false once the peer has gone away or stopped reading.
bool SendAll(int fd, const char* data, size_t size) {
  size_t sent = 0;
  while (sent < size) {
    const ssize_t n = ::send(fd, data + sent, size - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<size_t>(n);
  }
  return true;
}

bool SendAll(int fd, const std::string& bytes) { return SendAll(fd, bytes.data(), bytes.size()); }

// Copies `size` bytes of `in` to the socket a chunk at a time; stops early when the file
// ends sooner (it shrank) or the peer leaves.
void StreamBytes(int fd, std::istream& in, uintmax_t size) {
  std::vector<char> chunk(kStreamChunk);
  for (uintmax_t left = size; left > 0;) {
    in.read(chunk.data(), static_cast<std::streamsize>(std::min<uintmax_t>(left, chunk.size())));
    const auto got = static_cast<size_t>(in.gcount());
    if (got == 0 || !SendAll(fd, chunk.data(), got)) return;
    left -= got;
  }
}

// Streams a file: headers with its size, then its bytes (none for HEAD). A file that
// exists but cannot be opened or sized (permissions) answers 500.
void SendFile(int fd, const fs::path& file, bool head_only) {
  std::ifstream in(file, std::ios::binary);
  std::error_code ec;
  const uintmax_t size = fs::file_size(file, ec);
  if (!in || ec) {
    SendAll(fd, ErrorResponse(500, "Internal Server Error",
                              "cannot read " + file.filename().string(), head_only));
    return;
  }
  if (!SendAll(fd, ResponseHead(200, "OK", LabMimeType(file), size)) || head_only) return;
  StreamBytes(fd, in, size);
}

// ASCII lower case.
std::string Lowercase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// `text` without leading and trailing spaces and tabs.
std::string TrimBlanks(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The trimmed values of every header called `name` (lower case; matched ignoring case).
std::vector<std::string> HeaderValues(const std::string& head, const std::string& name) {
  std::vector<std::string> values;
  for (size_t start = head.find("\r\n"); start != std::string::npos;) {
    start += 2;
    const size_t end = head.find("\r\n", start);
    if (end == std::string::npos || end == start) break;
    const std::string line = head.substr(start, end - start);
    const size_t colon = line.find(':');
    if (colon != std::string::npos && Lowercase(line.substr(0, colon)) == name) {
      values.push_back(TrimBlanks(line.substr(colon + 1)));
    }
    start = end;
  }
  return values;
}

// True when a Host value names this server: 127.0.0.1, localhost or [::1] (any case) with
// our port (the port may be left out only when it is 80).
bool IsOwnHost(const std::string& host, int port) {
  const std::string lower = Lowercase(host);
  const std::string with_port = ":" + std::to_string(port);
  for (const std::string name : {"127.0.0.1", "localhost", "[::1]"}) {
    if (lower == name + with_port || (port == 80 && lower == name)) return true;
  }
  return false;
}

// Why a request's Host is refused, or empty when it names this server. A page of another
// site whose name was rebound to 127.0.0.1 still sends its own name, so it gets nothing.
// Every request needs exactly one Host, HTTP/1.0 too (browsers always send it).
std::string HostProblem(const std::string& head, int port) {
  const std::vector<std::string> hosts = HeaderValues(head, "host");
  if (hosts.empty()) return "the request has no Host header";
  if (hosts.size() > 1) return "the request has more than one Host header";
  if (IsOwnHost(hosts[0], port)) return "";
  return "Host '" + hosts[0] + "' is not this server (127.0.0.1:" + std::to_string(port) +
         ", localhost:" + std::to_string(port) + " or [::1]:" + std::to_string(port) + ")";
}

// Sends what a GET or HEAD of `target` names: the lesson's name, a file, or 404.
void ServeTarget(const LabSite& site, int fd, const std::string& target, bool head_only) {
  // lesson.json: which lesson is served (the page's title comes from its name).
  const auto clean = CleanUrlPath(target);
  if (clean && (*clean == "/lesson.json" || *clean == "/view.json")) {
    // A name that is not UTF-8 still goes out: its bad bytes become U+FFFD.
    const fs::path& served = *clean == "/view.json" ? site.model_file : site.lesson_file;
    const nlohmann::json about = {{"file", served.filename().string()}};
    const std::string body = about.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    SendAll(fd, TextResponse(200, "OK", "application/json", body, head_only));
    return;
  }
  const auto file = ResolveLabPath(site, target);
  if (!file) {
    SendAll(fd, ErrorResponse(404, "Not Found", target, head_only));
    return;
  }
  SendFile(fd, *file, head_only);
}

// Answers one complete request head ("GET /path HTTP/1.1\r\nHost: ...\r\n\r\n").
void Answer(const ServeContext& context, int fd, const std::string& head) {
  std::istringstream first_line(head.substr(0, head.find("\r\n")));
  std::string method, target, version;
  first_line >> method >> target >> version;
  if (version.rfind("HTTP/1.", 0) != 0) {
    SendAll(fd, ErrorResponse(400, "Bad Request", "not HTTP/1.x"));
    return;
  }
  const bool head_only = method == "HEAD";
  const std::string host_problem = HostProblem(head, context.port);
  if (!host_problem.empty()) {
    SendAll(fd, ErrorResponse(421, "Misdirected Request", host_problem, head_only));
  } else if (method != "GET" && !head_only) {
    SendAll(fd, ErrorResponse(405, "Method Not Allowed", "only GET and HEAD are served"));
  } else {
    ServeTarget(context.site, fd, target, head_only);
  }
}

// Milliseconds left until `deadline`, rounded up (0 once it has passed).
int MillisecondsLeft(Clock::time_point deadline) {
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
  return static_cast<int>(std::max<std::chrono::milliseconds::rep>(left.count(), 0));
}

// Waits until `fd` has bytes (or an end) to read; false when `deadline` passes first.
bool WaitReadable(int fd, Clock::time_point deadline) {
  for (int left; (left = MillisecondsLeft(deadline)) > 0;) {
    pollfd watch{fd, POLLIN, 0};
    const int ready = ::poll(&watch, 1, left);
    if (ready > 0) return true;
    if (ready < 0 && errno != EINTR) return false;
  }
  return false;
}

// How reading a request head ended.
enum class HeadRead { kComplete, kClosed, kTooLong, kTimedOut };

// Reads up to the blank line that ends a request head, all before `deadline`: one budget
// for every read, so a peer trickling a byte at a time is cut off as well.
HeadRead ReadRequestHead(int fd, Clock::time_point deadline, std::string& head) {
  char buffer[4096];
  while (head.find("\r\n\r\n") == std::string::npos) {
    if (head.size() >= kMaxRequestHead) return HeadRead::kTooLong;
    if (!WaitReadable(fd, deadline)) return HeadRead::kTimedOut;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) return HeadRead::kClosed;
    head.append(buffer, static_cast<size_t>(n));
  }
  return HeadRead::kComplete;
}

// Ends our side, drops a little of whatever the peer sent that we did not read (so the
// close does not reset the connection under our answer) and closes.
void CloseConnection(int fd) {
  ::shutdown(fd, SHUT_WR);
  char sink[4096];
  for (int i = 0; i < 16 && ::recv(fd, sink, sizeof sink, MSG_DONTWAIT) > 0; ++i) {
  }
  ::close(fd);
}

// Reads one request head from a connection and answers it. A connection that sent
// nothing before the deadline gets no word (like an idle preconnect).
void ServeConnection(const ServeContext& context, int fd) {
  const timeval send_timeout{kSendTimeoutSeconds, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &send_timeout, sizeof send_timeout);
  std::string head;
  const HeadRead outcome = ReadRequestHead(fd, Clock::now() + context.limits.head_deadline, head);
  if (outcome == HeadRead::kComplete) {
    Answer(context, fd, head);
  } else if (outcome == HeadRead::kTimedOut && !head.empty()) {
    SendAll(fd, ErrorResponse(408, "Request Timeout", "the request head took too long"));
  } else if (!head.empty()) {
    SendAll(fd, ErrorResponse(400, "Bad Request", "incomplete or oversized request head"));
  }
}

// A connection's whole life in its thread: served, then closed. No exception may leave
// the thread (it would end the process): one that comes up drops this connection only.
void HandleConnection(const ServeContext& context, int fd) noexcept {
  try {
    ServeConnection(context, fd);
  } catch (...) {
    // The answer may be half sent; closing is all that is left to do.
  }
  CloseConnection(fd);
}

// One of the server's connection slots, held while a connection's thread runs; the
// destructor gives it back on every way out, so another connection can come in.
class ConnectionSlot {
 public:
  // Takes a slot unless `limit` are taken already (then held() is false).
  ConnectionSlot(std::shared_ptr<std::atomic<int>> open, int limit) : open_(std::move(open)) {
    if (open_->fetch_add(1) >= limit) Release();
  }
  ConnectionSlot(ConnectionSlot&& other) noexcept = default;
  ConnectionSlot& operator=(ConnectionSlot&&) = delete;
  ~ConnectionSlot() { Release(); }
  bool held() const { return open_ != nullptr; }

 private:
  void Release() {
    if (open_) open_->fetch_sub(1);
    open_.reset();
  }
  std::shared_ptr<std::atomic<int>> open_;
};

// Answers 503 without reading the request, never blocking the accept loop, and closes.
void RefuseBusy(int fd) noexcept {
  try {
    const std::string reply =
        ErrorResponse(503, "Service Unavailable", "too many open connections, try again");
    ::send(fd, reply.data(), reply.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  } catch (...) {
    // Out of memory for the answer: the connection is closed without one.
  }
  CloseConnection(fd);
}

// Hands a new connection to a thread of its own, or refuses it at once when every slot is
// taken (or no thread can be started: out of threads or memory).
void Dispatch(const std::shared_ptr<const ServeContext>& context,
              const std::shared_ptr<std::atomic<int>>& open, int fd) noexcept {
  try {
    ConnectionSlot slot(open, context->limits.max_connections);
    if (slot.held()) {
      std::thread([context, fd, slot = std::move(slot)] { HandleConnection(*context, fd); })
          .detach();
      return;
    }
  } catch (...) {
    // the slot went back with the lambda; refuse below
  }
  RefuseBusy(fd);
}

// Says once per run of failures that accept() is failing and the server waits.
void ReportAcceptTrouble(int error, bool& reported) {
  if (reported) return;
  reported = true;
  std::cerr << "simlab lab: cannot accept connections (" << std::strerror(error)
            << "); retrying every " << kAcceptBackOff.count() << " ms" << std::endl;
}

// Text of the last socket error, for messages.
std::string SocketError(const std::string& what) {
  return "lab: " + what + ": " + std::strerror(errno);
}

// True when `dir` holds the lesson page.
bool HasLessonPage(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "web/lesson/index.html", ec);
}

// `start` or the nearest parent that holds the lesson page.
std::optional<fs::path> SearchUpwards(fs::path start) {
  for (fs::path dir = start; !dir.empty(); dir = dir.parent_path()) {
    if (HasLessonPage(dir)) return dir;
    if (dir == dir.parent_path()) break;
  }
  return std::nullopt;
}

// A file named on the command line (`what`: "lesson", "model") as an absolute path;
// refused unless it is a regular file.
fs::path GivenFile(const std::string& command, const std::string& what, const std::string& name) {
  std::error_code ec;
  const fs::path file = fs::absolute(name, ec);
  if (ec) throw Error(command + ": " + name + ": " + ec.message());
  if (fs::is_directory(file, ec)) throw Error(command + ": " + name + ": a folder, not a " + what + " file");
  if (!fs::is_regular_file(file, ec)) throw Error(command + ": no " + what + " file " + name);
  return file;
}

// The repository the page is served from (--root, or found), with its engine built.
fs::path ServedRepo(const std::string& command, const std::string& root) {
  std::error_code ec;
  const fs::path repo = root.empty() ? FindLabRepoRoot() : fs::absolute(root, ec);
  if (ec || !HasLessonPage(repo)) {
    throw Error(command + ": " + repo.string() + " has no web/lesson/index.html");
  }
  const std::string missing = MissingEngineProblem(repo);
  if (!missing.empty()) throw Error(command + ": " + missing);
  return repo;
}

// Serves until interrupted, printing the URL to `out`; returns the exit code.
int Serve(const std::string& command, const LabSite& site, int port, std::ostream& out) {
  LabServer server(site, port);
  const fs::path& served = site.model_file.empty() ? site.lesson_file : site.model_file;
  out << "simlab " << command << ": serving " << served.filename().string()
      << " at http://127.0.0.1:" << server.port() << "/ (Ctrl-C stops)" << std::endl;
  server.Serve();
  return 0;
}

int RunLab(const std::string& lesson, int port, const std::string& root, std::ostream& out) {
  const fs::path lesson_file = GivenFile("lab", "lesson", lesson);
  return Serve("lab", {ServedRepo("lab", root), lesson_file, {}}, port, out);
}

int RunView(const std::string& model, int port, const std::string& root, std::ostream& out) {
  const fs::path model_file = GivenFile("view", "model", model);
  return Serve("view", {ServedRepo("view", root), {}, model_file}, port, out);
}

}  // namespace

std::optional<fs::path> ResolveLabPath(const LabSite& site, const std::string& url_path) {
  const auto clean = CleanUrlPath(url_path);
  if (!clean) return std::nullopt;
  // The page itself and the lesson it shows, or the viewer and the model's folder.
  const bool viewer = !site.model_file.empty();
  if (*clean == "/" || *clean == "/index.html") {
    const fs::path page = viewer ? "web/view" : "web/lesson";
    return InsideRoot(site.repo_root / page, site.repo_root / page / "index.html");
  }
  if (viewer && clean->rfind("/model/", 0) == 0) {
    const fs::path folder = site.model_file.parent_path();
    return InsideRoot(folder, folder / clean->substr(7));
  }
  if (!viewer && *clean == "/lesson.txt") {
    return InsideRoot(site.lesson_file.parent_path(), site.lesson_file);
  }
  for (const Mount& mount : kMounts) {
    const std::string prefix = mount.prefix;
    if (clean->compare(0, prefix.size(), prefix) == 0) {
      const fs::path root = site.repo_root / mount.folder;
      return InsideRoot(root, root / clean->substr(prefix.size()));
    }
  }
  return std::nullopt;
}

std::string LabMimeType(const fs::path& file) {
  static const std::pair<const char*, const char*> kTypes[] = {
      {".html", "text/html; charset=utf-8"}, {".mjs", "text/javascript; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"}, {".wasm", "application/wasm"},
      {".css", "text/css; charset=utf-8"},     {".json", "application/json"},
      {".map", "application/json"},             {".txt", "text/plain; charset=utf-8"},
      {".xml", "application/xml"},              {".svg", "image/svg+xml"},
      {".png", "image/png"},                    {".jpg", "image/jpeg"},
      {".csv", "text/csv; charset=utf-8"},     {".woff2", "font/woff2"},
      {".woff", "font/woff"},                   {".ttf", "font/ttf"},
  };
  const std::string ext = file.extension().string();
  for (const auto& [known, type] : kTypes) {
    if (ext == known) return type;
  }
  return "application/octet-stream";
}

LabServer::LabServer(LabSite site, int port, LabLimits limits)
    : site_(std::move(site)), limits_(limits) {
  if (port < 0 || port > 65535) {
    throw Error("lab: --port " + std::to_string(port) + " is not a TCP port (0 to 65535)");
  }
  if (limits_.head_deadline.count() <= 0 || limits_.max_connections <= 0) {
    throw Error("lab: the request deadline and the connection cap must be positive");
  }
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (listen_fd_ < 0) throw Error(SocketError("socket"));
  const int yes = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(listen_fd_, 64) != 0) {
    const std::string message = SocketError("cannot listen on 127.0.0.1:" + std::to_string(port));
    ::close(listen_fd_);
    throw Error(message);
  }
  socklen_t length = sizeof address;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
}

LabServer::~LabServer() {
  Stop();
  ::close(listen_fd_);
}

LabAcceptAction LabAcceptErrorAction(int error) {
  switch (error) {
    // A signal, a connection that died while queued, or a network error accept()
    // passes on from the queued connection (accept(2) says to retry these at once).
    case EINTR:
    case ECONNABORTED:
    case EAGAIN:
    case EPROTO:
    case EPERM:
    case ENOPROTOOPT:
    case ENETDOWN:
    case ENETUNREACH:
    case EHOSTDOWN:
    case EHOSTUNREACH:
    case ENONET:
    case EOPNOTSUPP:
      return LabAcceptAction::kRetry;
    // The listening socket itself is gone (as after Stop()).
    case EBADF:
    case EINVAL:
    case ENOTSOCK:
    case EFAULT:
      return LabAcceptAction::kStop;
    // Out of descriptors or memory (EMFILE, ENFILE, ENOBUFS, ENOMEM: idle connections,
    // other processes) and anything unforeseen: wait a little and try again; the
    // pending connection stays queued meanwhile.
    default:
      return LabAcceptAction::kBackOff;
  }
}

void LabServer::Serve() {
  const auto context = std::make_shared<const ServeContext>(ServeContext{site_, port_, limits_});
  bool reported = false;
  while (!stopping_) {
    const int fd = ::accept(listen_fd_, nullptr, nullptr);
    if (fd >= 0) {
      reported = false;
      Dispatch(context, open_connections_, fd);
      continue;
    }
    // Failures: retry, back off and retry, or end (after Stop(), or with an error).
    const int error = errno;
    const LabAcceptAction action = LabAcceptErrorAction(error);
    if (stopping_) return;
    if (action == LabAcceptAction::kStop) {
      throw Error("lab: the listening socket failed: " + std::string(std::strerror(error)));
    }
    if (action == LabAcceptAction::kBackOff) {
      ReportAcceptTrouble(error, reported);
      std::this_thread::sleep_for(kAcceptBackOff);
    }
  }
}

void LabServer::Stop() {
  if (!stopping_.exchange(true)) ::shutdown(listen_fd_, SHUT_RDWR);
}

fs::path FindLabRepoRoot() {
  if (auto found = SearchUpwards(fs::current_path())) return *found;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    if (auto found = SearchUpwards(exe.parent_path())) return *found;
  }
  throw Error("lab: cannot find web/lesson/index.html above " +
              fs::current_path().string() + " or the simlab executable; pass --root");
}

std::string MissingEngineProblem(const fs::path& repo_root) {
  std::error_code ec;
  if (fs::is_regular_file(repo_root / "web/dist/simlab.mjs", ec) &&
      fs::is_regular_file(repo_root / "web/dist/simlab.wasm", ec)) {
    return "";
  }
  return "the WebAssembly engine is not built (" + (repo_root / "web/dist/simlab.mjs").string() +
         " is missing); build it once with: bash tools/install_deps.sh && bash tools/build_wasm.sh"
         " (about 12 minutes on 2 cores), then run this command again";
}

namespace {

// A subcommand serving a page for one file: `simlab NAME FILE [--port P] [--root R]`,
// run by `run(file, port, root, out)`.
using ServeRun = int (*)(const std::string& file, int port, const std::string& root, std::ostream& out);
void AddServeCommand(CLI::App& app, CommandIo& io, const char* name, const char* about,
                     const char* file_name, const char* file_help, int default_port, ServeRun run) {
  auto file = std::make_shared<std::string>();
  auto port = std::make_shared<int>(default_port);
  auto root = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(name, about);
  cmd->add_option(file_name, *file, file_help)->required();
  cmd->add_option("--port", *port, "TCP port on 127.0.0.1 (0 picks a free one)");
  cmd->add_option("--root", *root, "repository folder holding web/ and models/");
  cmd->callback([file, port, root, run, &io] { io.status = run(*file, *port, *root, *io.out); });
}

}  // namespace

void AddLabCommand(CLI::App& app, CommandIo& io) {
  AddServeCommand(app, io, "lab", "serve a lesson page with its live labs on 127.0.0.1", "lesson",
                  "lesson text file", 8765, RunLab);
}

void AddViewCommand(CLI::App& app, CommandIo& io) {
  AddServeCommand(app, io, "view", "serve the viewer of any model (and its folder) on 127.0.0.1",
                  "model", "MJCF model file", 8766, RunView);
}

}  // namespace simlab::apps
