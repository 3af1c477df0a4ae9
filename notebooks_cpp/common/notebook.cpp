// See notebook.hpp.
#include "notebook.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace nb {

std::string docs_dir(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : std::string(BL_SOURCE_DIR) + "/docs";
  std::filesystem::create_directories(dir + "/notebooks");
  return dir;
}

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.7g", v);
  return buf;
}

std::string sci(double v, int digits) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
  return buf;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

Markdown::Markdown(const std::string& path) : path_(path), file_(path) {
  if (!file_) throw std::runtime_error("cannot write " + path);
}

void Markdown::table(const std::vector<std::string>& header,
                     const std::vector<std::vector<std::string>>& rows) {
  auto line = [this](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const std::string& c : cells) s += " " + c + " |";
    *this << s << "\n";
  };
  line(header);
  std::string sep = "|";
  for (size_t i = 0; i < header.size(); ++i) sep += "---|";
  *this << sep << "\n";
  for (const auto& r : rows) line(r);
  *this << "\n";
}

void progress(const std::string& name, const std::string& message) {
  std::cout.flush();  // keep the Markdown on stdout and the progress on stderr in order
  static const auto t0 = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "[%s %6.1f s] %s\n", name.c_str(), s, message.c_str());
}

}  // namespace nb
