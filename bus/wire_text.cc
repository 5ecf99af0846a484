#include "bus/wire_text.h"

#include <glib.h>

namespace ahhs::bus {

bool IsWireText(std::string_view text) {
  // g_utf8_validate_len also refuses any NUL byte within the length.
  return text.size() <= kMaxWireText &&
         g_utf8_validate_len(text.data(), static_cast<gsize>(text.size()), nullptr);
}

std::string ToWireText(std::string_view text) {
  if (IsWireText(text)) return std::string(text);
  std::string clean(text);
  for (char& c : clean)
    if (c == '\0') c = '?';
  gchar* valid = g_utf8_make_valid(clean.data(), static_cast<gssize>(clean.size()));
  clean = valid;
  g_free(valid);
  if (clean.size() > kMaxWireText) {
    std::size_t cut = kMaxWireText - 3;
    while (cut > 0 && (static_cast<unsigned char>(clean[cut]) & 0xC0) == 0x80) --cut;
    clean = clean.substr(0, cut) + "...";
  }
  return clean;
}

}  // namespace ahhs::bus
