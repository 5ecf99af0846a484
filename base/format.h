// Number formatting shared by every program and file writer.
#pragma once

#include <cstdio>
#include <string>

namespace ahhs::base {

// The shortest-safe decimal text of a double: "%.17g", which reads back to the same double.
// Run stores, genome files, exports, golden vectors and command lines all write doubles so.
inline std::string ExactDouble(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace ahhs::base
