#include "tianracer_sim/scene/ogre_material.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tianracer_sim {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> tokens(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  auto flush = [&] {
    if (!cur.empty()) out.push_back(cur);
    cur.clear();
  };
  for (char c : line) {
    if (c == '{' || c == '}') {
      flush();
      out.emplace_back(1, c);
    } else if (c == ' ' || c == '\t' || c == '\r') {
      flush();
    } else {
      cur += c;
    }
  }
  flush();
  return out;
}

bool toFloat(const std::string& s, float* out) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) return false;
  *out = static_cast<float>(v);
  return true;
}

}  // namespace

std::vector<OgreMaterial> parseOgreMaterials(const std::string& text, const std::string& file,
                                             const WarningSink& warn) {
  std::vector<OgreMaterial> out;
  std::vector<std::string> stack;  // kinds of the open blocks
  std::string pending = "block";   // kind of the block the next '{' opens
  bool in_material = false;
  int techniques = 0;  // of the current material
  OgreMaterial cur;
  auto report = [&](int line, const std::string& what) {
    if (warn) warn(file + ":" + std::to_string(line) + ": " + what);
  };
  auto within = [&](const char* kind) { return std::find(stack.begin(), stack.end(), kind) != stack.end(); };

  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto comment = line.find("//");
    if (comment != std::string::npos) line.erase(comment);
    const std::vector<std::string> t = tokens(line);
    std::size_t i = 0;
    while (i < t.size()) {
      if (t[i] == "{") {
        stack.push_back(pending);
        if (pending == "technique" && in_material) ++techniques;
        pending = "block";
        ++i;
        continue;
      }
      if (t[i] == "}") {
        if (stack.empty()) {
          report(lineno, "'}' without a matching '{'");
        } else {
          if (stack.back() == "material" && in_material) {
            out.push_back(cur);
            in_material = false;
          }
          stack.pop_back();
        }
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < t.size() && t[j] != "{" && t[j] != "}") ++j;
      const std::vector<std::string> s(t.begin() + i, t.begin() + j);
      i = j;
      const std::string& kw = s[0];
      if (kw == "material" && stack.empty()) {
        if (s.size() < 2) {
          report(lineno, "'material' without a name");
          continue;
        }
        cur = OgreMaterial();
        cur.name = s[1];
        cur.file = file;
        cur.line = lineno;
        in_material = true;
        techniques = 0;
        if (s.size() >= 4 && s[2] == ":") {
          report(lineno, "material " + s[1] + " inherits from " + s[3] +
                             "; the parent's values are not read");
        }
        pending = "material";
        continue;
      }
      if (kw == "technique" || kw == "pass" || kw == "texture_unit") {
        pending = kw;
        continue;
      }
      pending = "block";  // any other block (programs, shadow casters...) is skipped
      if (!in_material || techniques != 1 || !within("pass") || !within("technique")) continue;
      const bool in_texture_unit = !stack.empty() && stack.back() == "texture_unit";
      const bool in_pass = !stack.empty() && stack.back() == "pass";
      if (in_pass && (kw == "ambient" || kw == "diffuse" || kw == "specular")) {
        if (s.size() >= 2 && s[1] == "vertexcolour") continue;
        std::vector<float> v;
        for (std::size_t k = 1; k < s.size(); ++k) {
          float f = 0.0f;
          if (!toFloat(s[k], &f)) {
            v.clear();
            break;
          }
          v.push_back(f);
        }
        const std::size_t need_max = kw == "specular" ? 5 : 4;
        if (v.size() < 3 || v.size() > need_max) {
          report(lineno, "material " + cur.name + ": '" + line + "' is not a colour; ignored");
          continue;
        }
        Eigen::Vector4f c(v[0], v[1], v[2], 1.0f);
        if (kw == "specular") {
          if (v.size() == 4) cur.shininess = v[3];
          if (v.size() == 5) {
            c[3] = v[3];
            cur.shininess = v[4];
          }
          cur.specular = c;
        } else {
          if (v.size() == 4) c[3] = v[3];
          (kw == "ambient" ? cur.ambient : cur.diffuse) = c;
        }
      } else if (in_texture_unit && kw == "texture" && cur.texture.empty()) {
        if (s.size() >= 2) cur.texture = s[1];
      } else if (in_texture_unit && kw == "scale") {
        float su = 0.0f, sv = 0.0f;
        if (s.size() == 3 && toFloat(s[1], &su) && toFloat(s[2], &sv) && su != 0.0f && sv != 0.0f) {
          cur.texture_scale = Eigen::Vector2f(su, sv);
        } else {
          report(lineno, "material " + cur.name + ": texture_unit '" + line +
                             "' is not 'scale <u> <v>' with non-zero values; ignored");
        }
      }
    }
  }
  if (!stack.empty()) report(lineno, "end of file inside a block (missing '}')");
  if (in_material) out.push_back(cur);
  return out;
}

std::optional<OgreMaterial> findOgreMaterial(const std::string& name,
                                             const std::vector<std::string>& folders,
                                             const WarningSink& warn) {
  for (const std::string& folder : folders) {
    std::vector<std::string> files;
    std::error_code ec;
    if (fs::is_directory(folder, ec)) {
      for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (entry.is_regular_file(ec) && entry.path().extension() == ".material") {
          files.push_back(entry.path().string());
        }
      }
      std::sort(files.begin(), files.end());
    } else if (fs::is_regular_file(folder, ec)) {
      files.push_back(folder);
    }
    for (const std::string& f : files) {
      std::ifstream in(f);
      std::stringstream ss;
      ss << in.rdbuf();
      for (OgreMaterial& m : parseOgreMaterials(ss.str(), f, warn)) {
        if (m.name == name) return m;
      }
    }
  }
  return std::nullopt;
}

}  // namespace tianracer_sim
