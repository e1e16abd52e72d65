#include "mini_xml.h"

#include <cctype>
#include <cstdlib>

namespace tianracer_sim {
namespace render_internal {

const XmlElement* XmlElement::child(const std::string& child_name) const {
  for (const auto& c : children) {
    if (c->name == child_name) return c.get();
  }
  return nullptr;
}

namespace {

std::string trim(const std::string& s) {
  const char* ws = " \t\n\r\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

class Reader {
 public:
  explicit Reader(const std::string& text) : s_(text) {}

  std::unique_ptr<XmlElement> document() {
    skipMisc();
    if (pos_ >= s_.size() || s_[pos_] != '<') fail("expected an element");
    auto root = element(0);
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw XmlError("XML line " + std::to_string(line_) + ": " + what);
  }

  bool startsWith(const char* lit) const { return s_.compare(pos_, std::char_traits<char>::length(lit), lit) == 0; }

  void advance(std::size_t n) {
    for (std::size_t i = 0; i < n && pos_ < s_.size(); ++i, ++pos_) {
      if (s_[pos_] == '\n') ++line_;
    }
  }

  void skipUntil(const char* terminator) {
    const auto end = s_.find(terminator, pos_);
    if (end == std::string::npos) fail(std::string("missing '") + terminator + "'");
    advance(end - pos_ + std::char_traits<char>::length(terminator));
  }

  void skipSpace() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) advance(1);
  }

  // Whitespace, the XML declaration, processing instructions, comments and a DOCTYPE.
  void skipMisc() {
    for (;;) {
      skipSpace();
      if (startsWith("<?")) {
        skipUntil("?>");
      } else if (startsWith("<!--")) {
        skipUntil("-->");
      } else if (startsWith("<!DOCTYPE")) {
        skipUntil(">");
      } else {
        return;
      }
    }
  }

  std::string name() {
    const std::size_t b = pos_;
    while (pos_ < s_.size()) {
      const char c = s_[pos_];
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
          c == ':') {
        ++pos_;
      } else {
        break;
      }
    }
    if (pos_ == b) fail("expected a name");
    return s_.substr(b, pos_ - b);
  }

  std::string decode(const std::string& raw) {
    std::string out;
    out.reserve(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out.push_back(raw[i]);
        continue;
      }
      const auto semi = raw.find(';', i);
      if (semi == std::string::npos) fail("unterminated entity");
      const std::string ent = raw.substr(i + 1, semi - i - 1);
      if (ent == "lt") out.push_back('<');
      else if (ent == "gt") out.push_back('>');
      else if (ent == "amp") out.push_back('&');
      else if (ent == "quot") out.push_back('"');
      else if (ent == "apos") out.push_back('\'');
      else if (!ent.empty() && ent[0] == '#') {
        const bool hex = ent.size() > 1 && (ent[1] == 'x' || ent[1] == 'X');
        const long code = std::strtol(ent.c_str() + (hex ? 2 : 1), nullptr, hex ? 16 : 10);
        if (code <= 0 || code > 0x7f) fail("unsupported character reference '&" + ent + ";'");
        out.push_back(static_cast<char>(code));
      } else {
        fail("unknown entity '&" + ent + ";'");
      }
      i = semi;
    }
    return out;
  }

  std::unique_ptr<XmlElement> element(int depth) {
    if (depth > 64) fail("elements nested too deeply");
    auto e = std::make_unique<XmlElement>();
    e->line = line_;
    advance(1);  // '<'
    e->name = name();
    for (;;) {
      skipSpace();
      if (pos_ >= s_.size()) fail("unterminated tag <" + e->name + ">");
      if (startsWith("/>")) {
        advance(2);
        return e;
      }
      if (s_[pos_] == '>') {
        advance(1);
        break;
      }
      const std::string key = name();
      skipSpace();
      if (pos_ >= s_.size() || s_[pos_] != '=') fail("expected '=' after attribute " + key);
      advance(1);
      skipSpace();
      if (pos_ >= s_.size() || (s_[pos_] != '"' && s_[pos_] != '\'')) {
        fail("expected a quoted value for attribute " + key);
      }
      const char quote = s_[pos_];
      advance(1);
      const auto end = s_.find(quote, pos_);
      if (end == std::string::npos) fail("unterminated attribute " + key);
      const std::string raw = s_.substr(pos_, end - pos_);
      advance(end - pos_ + 1);
      e->attributes[key] = decode(raw);
    }
    std::string text;
    for (;;) {
      if (pos_ >= s_.size()) fail("missing </" + e->name + ">");
      if (startsWith("<!--")) {
        skipUntil("-->");
      } else if (startsWith("<![CDATA[")) {
        advance(9);
        const auto end = s_.find("]]>", pos_);
        if (end == std::string::npos) fail("unterminated CDATA");
        text += s_.substr(pos_, end - pos_);
        advance(end - pos_ + 3);
      } else if (startsWith("<?")) {
        skipUntil("?>");
      } else if (startsWith("</")) {
        advance(2);
        const std::string closing = name();
        if (closing != e->name) fail("</" + closing + "> closes <" + e->name + ">");
        skipSpace();
        if (pos_ >= s_.size() || s_[pos_] != '>') fail("expected '>'");
        advance(1);
        e->text = trim(text);
        return e;
      } else if (s_[pos_] == '<') {
        e->children.push_back(element(depth + 1));
      } else {
        const auto next = s_.find('<', pos_);
        const std::size_t end = next == std::string::npos ? s_.size() : next;
        text += decode(s_.substr(pos_, end - pos_));
        advance(end - pos_);
      }
    }
  }

  const std::string& s_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

std::unique_ptr<XmlElement> parseXml(const std::string& text) { return Reader(text).document(); }

}  // namespace render_internal
}  // namespace tianracer_sim
