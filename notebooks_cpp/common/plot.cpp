// See plot.hpp.
#include "plot.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace nb {

std::string datablock(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::string s = "$" + name + " << EOD\n";
  char buf[40];
  for (const auto& r : rows) {
    for (size_t i = 0; i < r.size(); ++i) {
      if (std::isnan(r[i]))
        s += "NaN";
      else {
        std::snprintf(buf, sizeof buf, "%.9g", r[i]);
        s += buf;
      }
      s += i + 1 < r.size() ? " " : "\n";
    }
  }
  return s + "EOD\n";
}

void run_gnuplot(const std::string& script) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw std::runtime_error("gnuplot not found on PATH (apt-get install gnuplot-nox)");
  FILE* p = popen("gnuplot", "w");
  if (!p) throw std::runtime_error("cannot start gnuplot");
  std::fwrite(script.data(), 1, script.size(), p);
  if (pclose(p) != 0) throw std::runtime_error("gnuplot failed (script above on stderr)");
}

}  // namespace nb
