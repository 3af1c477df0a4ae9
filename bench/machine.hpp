// What the summary records about where it ran: core count (as nproc counts), CPU model, compiler.
#pragma once

#include <string>

namespace blb {

struct MachineInfo {
  int nproc;
  std::string cpu;       // "model name" of /proc/cpuinfo
  std::string compiler;  // compiler and version, build type and flags
};

MachineInfo machine_info();

}  // namespace blb
