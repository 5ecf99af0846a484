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

// A word a POSIX shell reads back as `s`: as it is when it has only safe characters, else in
// single quotes. For the follow-up commands programs print ("continue with: ...").
inline std::string ShellWord(const std::string& s) {
  const bool safe = !s.empty() && s.find_first_not_of(
                                      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnop"
                                      "qrstuvwxyz0123456789_./:=@%+,-") == std::string::npos;
  if (safe) return s;
  std::string quoted = "'";
  for (char c : s) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace ahhs::base
