// Running the `lcspice` binary from tests and reading what it wrote.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace lcs::cli_testing {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out, err;
  std::string err_line(size_t k) const {
    std::istringstream is(err);
    std::string line;
    for (size_t i = 0; i <= k; ++i)
      if (!std::getline(is, line)) return "";
    return line;
  }
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

inline fs::path scratch_root() {
  return fs::temp_directory_path() / ("lcspice-test-" + std::to_string(::getpid()));
}

// Removes this process's scratch directories when the test program ends.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(scratch_root(), ignored);
  }
};
inline ::testing::Environment* const kScratchCleanup =
    ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

// A fresh scratch directory per test.
inline fs::path scratch_dir(const std::string& name) {
  fs::path dir = scratch_root() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `lcspice ARGS` (ARGS already quoted as needed) with no standard input.
inline Result run_lcspice(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = std::string("'") + LCSPICE_BINARY + "' " + args + " </dev/null >'" +
                          out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline fs::path source_path(const std::string& relative) {
  return fs::path(LCSPICE_SOURCE_DIR) / relative;
}

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string f;
  bool quoted = false;
  for (size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
        f += '"';
        ++k;
      } else if (c == '"') {
        quoted = false;
      } else {
        f += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(f);
      f.clear();
    } else {
      f += c;
    }
  }
  fields.push_back(f);
  return fields;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<std::vector<std::string>> raw;
  int column(const std::string& name) const {
    for (size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return static_cast<int>(k);
    return -1;
  }
};

inline Csv parse_csv(const std::string& text) {
  Csv csv;
  std::istringstream is(text);
  std::string line;
  if (std::getline(is, line)) csv.header = split_csv_line(line);
  while (std::getline(is, line)) {
    if (line.empty()) continue;
    auto fields = split_csv_line(line);
    std::vector<double> values;
    for (const std::string& f : fields) values.push_back(std::strtod(f.c_str(), nullptr));
    csv.rows.push_back(values);
    csv.raw.push_back(fields);
  }
  return csv;
}

// circuits/NAME.cir in the source tree.
inline fs::path circuit(const std::string& name) { return source_path("circuits/" + name + ".cir"); }

// `lcspice run NETLIST [--method METHOD] EXTRA` into a scratch directory; its CSV (exit 0 expected).
inline Csv run_csv(const fs::path& netlist, const std::string& method, const std::string& extra = "") {
  static int serial = 0;
  const fs::path dir = scratch_dir("run_csv_" + std::to_string(++serial));
  const Result r = run_lcspice("run '" + netlist.string() + "'" + (method.empty() ? "" : " --method " + method) +
                                   " -o '" + (dir / "out.csv").string() + "' " + extra,
                               dir);
  EXPECT_EQ(r.code, 0) << netlist << " --method " << method << ": " << r.err;
  return parse_csv(read_file(dir / "out.csv"));
}

// One column of a CSV by its header name (a failure when there is none).
inline std::vector<double> column(const Csv& csv, const std::string& name) {
  const int c = csv.column(name);
  EXPECT_GE(c, 0) << "no column " << name;
  std::vector<double> out;
  if (c >= 0)
    for (const std::vector<double>& row : csv.rows) out.push_back(row[c]);
  return out;
}

// A netlist written to a scratch directory of its own (named after `prefix` and `name`).
inline fs::path write_deck(const std::string& prefix, const std::string& name, const std::string& text) {
  const fs::path path = scratch_dir(prefix + name) / (name + ".cir");
  std::ofstream(path) << text;
  return path;
}

// The index of the row nearest to time t.
inline size_t row_at(const std::vector<double>& times, double t) {
  size_t best = 0;
  for (size_t k = 1; k < times.size(); ++k)
    if (std::abs(times[k] - t) < std::abs(times[best] - t)) best = k;
  return best;
}

}  // namespace lcs::cli_testing
