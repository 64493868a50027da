// JSON output helpers; see json_out.hpp.
#include "json_out.hpp"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_error.hpp"

namespace wedge::cli {

std::string first_non_finite(const OutJson& j, const std::string& path) {
  switch (j.type()) {
    case OutJson::value_t::number_float: return std::isfinite(j.get<double>()) ? "" : (path.empty() ? "value" : path);
    case OutJson::value_t::array:
      for (std::size_t i = 0; i < j.size(); ++i)
        if (std::string p = first_non_finite(j[i], path + "[" + std::to_string(i) + "]"); !p.empty()) return p;
      return "";
    case OutJson::value_t::object:
      for (const auto& [key, value] : j.items())
        if (std::string p = first_non_finite(value, path.empty() ? key : path + "." + key); !p.empty()) return p;
      return "";
    default: return "";
  }
}

OutputSink::OutputSink(const std::string& path) : path_(path) {
  if (path_.empty()) {  // stdout: buffered in an anonymous file, copied out by commit()
    file_ = std::tmpfile();
    if (file_ == nullptr) throw Failure(std::string("cannot create a temporary file (") + std::strerror(errno) + ")");
    return;
  }
  temp_path_ = path_ + ".tmp.XXXXXX";
  const int fd = ::mkstemp(temp_path_.data());
  if (fd < 0) throw Failure(path_ + ": cannot create output file (" + std::strerror(errno) + ")");
  // mkstemp makes the file private (0600); give it the permissions a plain fopen would have.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  file_ = ::fdopen(fd, "w");
  if (file_ == nullptr) {
    const int err = errno;
    ::close(fd);
    std::remove(temp_path_.c_str());
    throw Failure(path_ + ": cannot create output file (" + std::strerror(err) + ")");
  }
}

OutputSink::~OutputSink() {
  if (file_ != nullptr) std::fclose(file_);
  if (!temp_path_.empty() && !committed_) std::remove(temp_path_.c_str());
}

void OutputSink::write_line(const std::string& line) {
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fputc('\n', file_) == EOF)
    throw Failure((path_.empty() ? std::string("stdout") : path_) + ": write failed (" + std::strerror(errno) + ")");
}

void OutputSink::commit() {
  if (path_.empty()) {
    std::rewind(file_);
    char buffer[1 << 16];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, file_)) > 0)
      if (std::fwrite(buffer, 1, n, stdout) != n) break;
    const bool ok = !std::ferror(file_) && std::fflush(stdout) == 0 && !std::ferror(stdout);
    std::fclose(file_);
    file_ = nullptr;
    if (!ok) throw Failure(std::string("stdout: write failed (") + std::strerror(errno) + ")");
    committed_ = true;
    return;
  }
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) throw Failure(path_ + ": write failed (" + std::strerror(errno) + ")");
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0)
    throw Failure(path_ + ": cannot rename the output into place (" + std::strerror(errno) + ")");
  committed_ = true;
}

}  // namespace wedge::cli
