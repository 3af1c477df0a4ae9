// What every notebook shares: where its output goes, a Markdown stream that writes to stdout and to
// docs/notebooks/<name>.md at once, number formatting, and progress lines on stderr.
#pragma once

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace nb {

// The docs directory: argv[1] when given, else <source>/docs. Notebooks write their .md and PNGs into
// its notebooks/ folder (created if missing); docs_dir returns the docs directory itself.
std::string docs_dir(int argc, char** argv);

// Shortest round-trip-ish form of an input value ("%.7g": 0.999999, 1e-09, 1000.3).
std::string num(double v);

// "1.2e-05" style with `digits` significant digits; "0" for 0, "NaN"/"inf" as such.
std::string sci(double v, int digits = 2);
// Fixed with `decimals` decimals.
std::string fixed(double v, int decimals = 1);

// Markdown to stdout and to a file at once.
class Markdown {
 public:
  explicit Markdown(const std::string& path);
  template <class V>
  Markdown& operator<<(const V& v) {
    std::ostringstream s;
    s << v;
    std::cout << s.str();
    file_ << s.str();
    return *this;
  }
  // A pipe table; every row must have header.size() cells.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream file_;
};

// "[name  12.3 s] message" on stderr, so long runs show where they are without polluting stdout.
void progress(const std::string& name, const std::string& message);

}  // namespace nb
