#include "cli/csv_writer.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <unistd.h>

#include "cli/atomic_file.h"
#include "cli/exit_codes.h"

namespace lcs {

std::string csv_quote(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

CsvSink::CsvSink(std::string path) : path_(std::move(path)) {
  if (path_.empty() || path_ == "-") {
    to_stdout_ = true;
    out_ = stdout;
    return;
  }
  const AtomicTarget target = atomic_target(path_);
  if (!target.replace) {  // a device or FIFO (/dev/null, a pipe): write into it in place
    out_ = std::fopen(path_.c_str(), "w");
    if (!out_) throw CliError(kExitUsage, "error: cannot write '" + path_ + "': " + std::strerror(errno));
    in_place_ = true;
    return;
  }
  final_path_ = target.path;
  const int fd = create_temp_beside(target, &temp_path_);
  if (fd < 0)
    throw CliError(kExitUsage, "error: cannot write '" + path_ + "': " + std::strerror(errno));
  out_ = fdopen(fd, "w");
}

CsvSink::~CsvSink() {
  if (in_place_ && !finished_ && out_) {
    std::fclose(out_);
    return;
  }
  if (!to_stdout_ && !finished_ && out_) {
    std::fclose(out_);
    std::remove(temp_path_.c_str());
    release_temp(temp_path_);
  }
}

void CsvSink::begin(const std::vector<std::string>& names) {
  std::fputs("time", out_);
  for (const std::string& n : names) {
    std::fputc(',', out_);
    std::fputs(csv_quote(n).c_str(), out_);
  }
  std::fputc('\n', out_);
}

// "%.14e" for every number, by std::to_chars (which is specified to print what printf prints,
// and is several times faster: a 1000-diode circuit's rows of 2000 columns made printf a quarter
// of the run).
void CsvSink::row(double t, const Eigen::VectorXd& values) {
  ++rows_;
  line_.resize(24 * (values.size() + 1) + 1);
  char* p = line_.data();
  char* const end = p + line_.size();
  p = std::to_chars(p, end, t, std::chars_format::scientific, 14).ptr;
  for (int k = 0; k < values.size(); ++k) {
    *p++ = ',';
    p = std::to_chars(p, end, values(k), std::chars_format::scientific, 14).ptr;
  }
  *p++ = '\n';
  std::fwrite(line_.data(), 1, p - line_.data(), out_);
}

void CsvSink::finish() {
  if (finished_) return;
  finished_ = true;
  if (to_stdout_) {
    std::fflush(out_);
    return;
  }
  if (in_place_) {
    std::fclose(out_);
    out_ = nullptr;
    return;
  }
  const bool ok = std::fflush(out_) == 0 && fsync(fileno(out_)) == 0;
  std::fclose(out_);
  out_ = nullptr;
  const bool renamed = ok && std::rename(temp_path_.c_str(), final_path_.c_str()) == 0;
  release_temp(temp_path_);
  if (!renamed) {
    std::remove(temp_path_.c_str());
    throw CliError(kExitUsage, "error: cannot write '" + path_ + "': " + std::strerror(errno));
  }
}

}  // namespace lcs
