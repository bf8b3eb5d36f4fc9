#include "tools/campaign/xml_scan.h"

#include <cctype>

namespace criticality::campaign {
namespace {

std::string Decode(const std::string& s) {
  if (s.find('&') == std::string::npos) return s;
  static const std::pair<const char*, char> kEntities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    bool done = false;
    if (s[i] == '&') {
      for (const auto& [name, c] : kEntities) {
        if (s.compare(i, std::char_traits<char>::length(name), name) == 0) {
          out += c;
          i += std::char_traits<char>::length(name);
          done = true;
          break;
        }
      }
    }
    if (!done) out += s[i++];
  }
  return out;
}

bool IsNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
         c == ':';
}

}  // namespace

void ScanXmlTags(const std::string& text,
                 const std::function<void(const std::string&, const XmlAttributes&)>& on_tag) {
  const std::size_t n = text.size();
  std::size_t i = 0;
  while (true) {
    i = text.find('<', i);
    if (i == std::string::npos || i + 1 >= n) return;
    if (text.compare(i, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", i + 4);
      if (end == std::string::npos) return;
      i = end + 3;
      continue;
    }
    if (text.compare(i, 9, "<![CDATA[") == 0) {
      const std::size_t end = text.find("]]>", i + 9);
      if (end == std::string::npos) return;
      i = end + 3;
      continue;
    }
    if (text[i + 1] == '?' || text[i + 1] == '!' || text[i + 1] == '/') {
      const std::size_t end = text.find('>', i + 1);
      if (end == std::string::npos) return;
      i = end + 1;
      continue;
    }
    std::size_t p = i + 1;
    const std::size_t name_start = p;
    while (p < n && IsNameChar(text[p])) ++p;
    const std::string name = text.substr(name_start, p - name_start);
    XmlAttributes attrs;
    while (p < n) {
      while (p < n && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
      if (p >= n || text[p] == '>' || text[p] == '/') break;
      const std::size_t a = p;
      while (p < n && IsNameChar(text[p])) ++p;
      const std::string key = text.substr(a, p - a);
      while (p < n && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
      if (key.empty() || p >= n || text[p] != '=') {
        ++p;  // malformed: skip a character and go on
        continue;
      }
      ++p;
      while (p < n && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
      if (p >= n || (text[p] != '"' && text[p] != '\'')) continue;
      const char quote = text[p++];
      const std::size_t v = p;
      while (p < n && text[p] != quote) ++p;
      attrs[key] = Decode(text.substr(v, p - v));
      ++p;
    }
    const std::size_t end = text.find('>', p);
    if (!name.empty()) on_tag(name, attrs);
    if (end == std::string::npos) return;
    i = end + 1;
  }
}

}  // namespace criticality::campaign
