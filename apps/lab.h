// `simlab lab LESSON.txt [--port P]`: serves the lesson page on 127.0.0.1 (a small
// static HTTP/1.1 GET/HEAD server): web/lesson (the page), web/lab (the live lab), web/dist
// (the engine in WebAssembly), the three and uplot packages, the lesson text and models/.
// `simlab view MODEL.xml [--port P]`: the same server with the viewer page (web/view)
// and the model's own folder under /model/.
// Only requests whose Host names this server are answered (DNS-rebinding defence), a
// request head must arrive within a total deadline, and open connections are capped.
#ifndef SIMLAB_APPS_LAB_H_
#define SIMLAB_APPS_LAB_H_

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli.h"

namespace CLI {
class App;
}

namespace simlab::apps {

// What the server may hand out: the repository (for web/ and models/), and the lesson
// (simlab lab) or the model whose folder it serves (simlab view).
struct LabSite {
  std::filesystem::path repo_root;
  std::filesystem::path lesson_file;
  std::filesystem::path model_file;
};

// The file a URL path names, or nothing when it is outside every allowed root
// ("..", unknown prefixes, missing files).
std::optional<std::filesystem::path> ResolveLabPath(const LabSite& site,
                                                    const std::string& url_path);

// Content-Type for a file by its extension (application/wasm, text/javascript, ...).
std::string LabMimeType(const std::filesystem::path& file);

// How long and how many: a connection must deliver its whole request head within
// head_deadline (one budget for all its reads, so a peer trickling bytes is cut off too),
// and at most max_connections are served at once (one more is answered 503 at once).
struct LabLimits {
  std::chrono::milliseconds head_deadline{10000};
  int max_connections = 64;
};

// What the accept loop does when accept() fails with an errno value.
enum class LabAcceptAction {
  kRetry,    // at once: EINTR, ECONNABORTED, network errors of the queued connection
  kBackOff,  // after a short sleep: out of descriptors or memory (EMFILE, ENFILE, ENOBUFS,
             // ENOMEM) or an error not foreseen
  kStop,     // the listening socket is gone (EBADF, EINVAL after Stop())
};
LabAcceptAction LabAcceptErrorAction(int error);

// A listening socket on 127.0.0.1 that serves `site`, one thread per connection. Nothing
// thrown while serving a connection leaves its thread, and running out of descriptors or
// memory only makes the server wait and try again.
class LabServer {
 public:
  // Binds 127.0.0.1:port (0 = any free port). Throws simlab::Error when it cannot or
  // when the limits are not positive.
  LabServer(LabSite site, int port, LabLimits limits = {});
  ~LabServer();
  LabServer(const LabServer&) = delete;
  LabServer& operator=(const LabServer&) = delete;

  int port() const { return port_; }
  // Accepts connections until Stop(); throws simlab::Error only if the listening socket
  // fails without Stop().
  void Serve();
  // Makes Serve() return (from any thread).
  void Stop();

 private:
  LabSite site_;
  LabLimits limits_;
  // Connections being served; shared with their detached threads, which may outlive us.
  std::shared_ptr<std::atomic<int>> open_connections_ = std::make_shared<std::atomic<int>>(0);
  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stopping_{false};
};

// Finds the repository (the folder holding web/lesson/index.html) from the current
// directory or the executable's location; throws simlab::Error when there is none.
std::filesystem::path FindLabRepoRoot();

// Why the page cannot run in the repository: the WebAssembly engine is not built (with
// how to build it), or empty when web/dist/simlab.mjs is there.
std::string MissingEngineProblem(const std::filesystem::path& repo_root);

// Registers the subcommands; each prints the URL to io.out and serves until interrupted.
void AddLabCommand(CLI::App& app, CommandIo& io);
void AddViewCommand(CLI::App& app, CommandIo& io);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_LAB_H_
