#include "bowg/core/resident_memory.h"

#include <unistd.h>

#include <fstream>

namespace bowg {

double residentBytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0, pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return 0;
  return pages_resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

}  // namespace bowg
