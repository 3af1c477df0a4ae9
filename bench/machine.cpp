// Machine description for the summary; see machine.hpp.
#include "machine.hpp"

#include <sched.h>
#include <unistd.h>

#include <fstream>

namespace blb {

MachineInfo machine_info() {
  MachineInfo m;
  cpu_set_t set;
  m.nproc = sched_getaffinity(0, sizeof(set), &set) == 0
                ? CPU_COUNT(&set)
                : static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  m.cpu = "unknown";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon != std::string::npos) m.cpu = line.substr(line.find_first_not_of(" \t", colon + 1));
    break;
  }
#if defined(__clang__)
  m.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  m.compiler = "GCC " __VERSION__;
#else
  m.compiler = "unknown compiler";
#endif
  std::string flags = BLB_CXX_FLAGS;
  flags.erase(0, flags.find_first_not_of(' '));
  m.compiler += ", " BLB_BUILD_TYPE " build, flags: " + flags;
  return m;
}

}  // namespace blb
