// Waveform CSV (SPEC §3): header `time,<probe>,...`, RFC 4180 quoting, one row per output time,
// 15 significant digits. A regular file is written to a temporary name beside it and renamed
// into place by finish(), so a reader never sees a torn file; a device or FIFO (/dev/null, a
// pipe) is written in place, never replaced.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "solver/integrators/output_sink.h"

namespace lcs {

class CsvSink : public OutputSink {
 public:
  explicit CsvSink(std::string path);  // "-" or "": standard output. Throws CliError (exit 1).
  ~CsvSink() override;                 // removes the temporary file if finish() never ran
  void begin(const std::vector<std::string>& names) override;
  void row(double t, const Eigen::VectorXd& values) override;
  void finish() override;
  const std::string& path() const { return path_; }
  long rows() const { return rows_; }
  // A regular file, written through a temporary and renamed: a later sink on the same path
  // replaces what this one wrote (standard output and devices or pipes cannot be rewritten).
  bool replaceable() const { return !to_stdout_ && !in_place_; }

 private:
  std::string path_, final_path_, temp_path_;
  std::FILE* out_ = nullptr;
  std::vector<char> line_;  // one row's text
  bool to_stdout_ = false, in_place_ = false, finished_ = false;
  long rows_ = 0;
};



std::string csv_quote(const std::string& field);

}  // namespace lcs
