#include "lab.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
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
    {"/dist/", "web/dist"},
    {"/node_modules/three/", "web/node_modules/three"},
    {"/node_modules/uplot/", "web/node_modules/uplot"},
    {"/models/", "models"},
};

// Largest request head we read; anything longer is refused.
constexpr size_t kMaxRequestHead = 16384;

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

// Reads a whole file as bytes.
std::string ReadFileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Every file="..." a model's XML names, relative to its folder, recursively for XML.
// Absolute names and names that leave the folder (also through links) are skipped.
void CollectModelFiles(const fs::path& folder, const std::string& relative,
                       std::set<std::string>& found) {
  static const std::regex kFileAttribute(R"(\bfile\s*=\s*["']([^"']+)["'])");
  const std::string xml = ReadFileBytes(folder / relative);
  for (std::sregex_iterator it(xml.begin(), xml.end(), kFileAttribute), end; it != end; ++it) {
    const std::string name = (*it)[1].str();
    if (name[0] == '/' || fs::path(name).has_root_path() || ClimbsOut(name)) continue;
    if (!found.insert(name).second) continue;
    if (fs::path(name).extension() == ".xml" && InsideRoot(folder, folder / name)) {
      CollectModelFiles(folder, name, found);
    }
  }
}

// One HTTP response with a body and the headers every answer carries.
std::string HttpResponse(int status, const std::string& reason, const std::string& type,
                         const std::string& body, bool head_only) {
  std::ostringstream out;
  out << "HTTP/1.1 " << status << " " << reason << "\r\n"
      << "Content-Type: " << type << "\r\n"
      << "Content-Length: " << body.size() << "\r\n"
      << "Cache-Control: no-store\r\n"
      << "X-Content-Type-Options: nosniff\r\n"
      << "Connection: close\r\n\r\n";
  if (!head_only) out << body;
  return out.str();
}

// A plain-text error answer.
std::string HttpError(int status, const std::string& reason, const std::string& detail) {
  return HttpResponse(status, reason, "text/plain; charset=utf-8",
                      std::to_string(status) + " " + reason + ": " + detail + "\n", false);
}

// The answer to one request head ("GET /path HTTP/1.1\r\n...").
std::string Answer(const LabSite& site, const std::string& head) {
  std::istringstream first_line(head.substr(0, head.find("\r\n")));
  std::string method, target, version;
  first_line >> method >> target >> version;
  if (version.rfind("HTTP/1.", 0) != 0) return HttpError(400, "Bad Request", "not HTTP/1.x");
  const bool head_only = method == "HEAD";
  if (method != "GET" && !head_only) {
    return HttpError(405, "Method Not Allowed", "only GET and HEAD are served");
  }
  const auto clean = CleanUrlPath(target);
  // models/NAME.files.json: the files a model pulls in, for the lab's loader.
  static const std::regex kFilesJson(R"(^/models/([A-Za-z0-9_.-]+\.xml)\.files\.json$)");
  std::smatch match;
  if (clean && std::regex_match(*clean, match, kFilesJson)) {
    if (auto model = ResolveLabPath(site, "/models/" + match[1].str())) {
      return HttpResponse(200, "OK", "application/json", LabModelFilesJson(*model), head_only);
    }
  }
  // lesson.json: which lesson is served (the page's title comes from its name).
  if (clean && *clean == "/lesson.json") {
    const nlohmann::json about = {{"file", site.lesson_file.filename().string()}};
    return HttpResponse(200, "OK", "application/json", about.dump(), head_only);
  }
  const auto file = clean ? ResolveLabPath(site, *clean) : std::nullopt;
  if (!file) return HttpError(404, "Not Found", target);
  return HttpResponse(200, "OK", LabMimeType(*file), ReadFileBytes(*file), head_only);
}

// Sends all of `bytes` (a peer that went away is not our problem).
void SendAll(int fd, const std::string& bytes) {
  size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<size_t>(n);
  }
}

// Reads one request head from a connection, answers it and closes it.
void HandleConnection(const LabSite& site, int fd) {
  timeval timeout{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::string head;
  char buffer[4096];
  while (head.find("\r\n\r\n") == std::string::npos && head.size() < kMaxRequestHead) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    head.append(buffer, static_cast<size_t>(n));
  }
  if (head.find("\r\n\r\n") != std::string::npos) {
    SendAll(fd, Answer(site, head));
  } else if (!head.empty()) {
    SendAll(fd, HttpError(400, "Bad Request", "incomplete or oversized request head"));
  }
  ::close(fd);
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

// Serves until interrupted; returns the exit code.
int RunLab(const std::string& lesson, int port, const std::string& root) {
  const fs::path lesson_file = fs::absolute(lesson);
  if (!fs::is_regular_file(lesson_file)) {
    throw Error("lab: no lesson file " + lesson);
  }
  const fs::path repo = root.empty() ? FindLabRepoRoot() : fs::absolute(root);
  if (!HasLessonPage(repo)) {
    throw Error("lab: " + repo.string() + " has no web/lesson/index.html");
  }
  LabServer server({repo, lesson_file}, port);
  std::cout << "simlab lab: serving " << lesson_file.filename().string() << " at http://127.0.0.1:"
            << server.port() << "/ (Ctrl-C stops)" << std::endl;
  server.Serve();
  return 0;
}

}  // namespace

std::optional<fs::path> ResolveLabPath(const LabSite& site, const std::string& url_path) {
  const auto clean = CleanUrlPath(url_path);
  if (!clean) return std::nullopt;
  // The page itself and the lesson it shows.
  if (*clean == "/" || *clean == "/index.html") {
    return InsideRoot(site.repo_root / "web/lesson", site.repo_root / "web/lesson/index.html");
  }
  if (*clean == "/lesson.txt") return InsideRoot(site.lesson_file.parent_path(), site.lesson_file);
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
      {".csv", "text/csv; charset=utf-8"},
  };
  const std::string ext = file.extension().string();
  for (const auto& [known, type] : kTypes) {
    if (ext == known) return type;
  }
  return "application/octet-stream";
}

std::string LabModelFilesJson(const fs::path& model_file) {
  std::set<std::string> found;
  CollectModelFiles(model_file.parent_path(), model_file.filename().string(), found);
  nlohmann::json out = {{"model", model_file.filename().string()},
                        {"files", std::vector<std::string>(found.begin(), found.end())}};
  return out.dump();
}

LabServer::LabServer(LabSite site, int port) : site_(std::move(site)) {
  if (port < 0 || port > 65535) {
    throw Error("lab: --port " + std::to_string(port) + " is not a TCP port (0 to 65535)");
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

void LabServer::Serve() {
  while (!stopping_) {
    const int fd = ::accept(listen_fd_, nullptr, nullptr);
    if (fd < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      return;  // Stop() shut the socket down
    }
    std::thread([site = site_, fd] { HandleConnection(site, fd); }).detach();
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

void AddLabCommand(CLI::App& app) {
  auto lesson = std::make_shared<std::string>();
  auto port = std::make_shared<int>(8765);
  auto root = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("lab", "serve a lesson page with its live labs on 127.0.0.1");
  cmd->add_option("lesson", *lesson, "lesson text file")->required();
  cmd->add_option("--port", *port, "TCP port on 127.0.0.1 (0 picks a free one)");
  cmd->add_option("--root", *root, "repository folder holding web/ and models/");
  cmd->callback([lesson, port, root] { std::exit(RunLab(*lesson, *port, *root)); });
}

}  // namespace simlab::apps
