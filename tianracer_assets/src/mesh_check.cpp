// What assimp 5.2 (Debian 12's libassimp5) trusts in a mesh file, checked first. Each check
// names the assimp code that would otherwise crash (code/AssetLib/Collada/ColladaParser.cpp,
// ColladaLoader.cpp; Debian builds assimp with its debug assertions, so a failed ai_assert
// aborts the process). Gazebo classic's own loaders check no more (gazebo/common/
// ColladaLoader.cc LoadTriangles indexes its vertices with the <p> values unchecked and
// LoadNode follows <instance_node> with no visited set; STLLoader.cc stops at a short read):
// a file either loads there or takes gzserver down, so refusing it with a message loses nothing
// that Gazebo loads.
#include "mesh_check.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <assimp/scene.h>
#include <tinyxml2.h>

#include "tianracer_assets/mesh.h"

namespace tianracer_assets {
namespace mesh_check {

bool looksLikeCollada(const std::string& path) {
  std::string ext;
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "dae") return true;
  if (ext == "stl" || ext == "obj") return false;  // assimp's importer by extension
  // assimp's ColladaLoader::CanRead looks for "<collada" in the first 200 bytes; a longer
  // look costs nothing and misses no prologue.
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  for (char& c : head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return head.find("<collada") != std::string::npos;
}

namespace {

using tinyxml2::XMLElement;
using tinyxml2::XMLNode;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// The text assimp reads of an element: pugixml's node.text(), the first text or CDATA child
// (tinyxml2's GetText() only looks at the first child).
const char* textOf(const XMLElement* e) {
  for (const XMLNode* n = e->FirstChild(); n; n = n->NextSibling()) {
    if (const tinyxml2::XMLText* t = n->ToText()) return t->Value();
  }
  return "";
}

// A token of a list: [b, b + n), inside the element's text (no copy: lists hold millions).
struct Token {
  const char* b;
  std::size_t n;
  std::string str() const { return std::string(b, std::min<std::size_t>(n, 40)); }
};

// Calls f(token) for each whitespace-separated token; stops when f returns false.
template <class F>
void forEachToken(const char* s, F f) {
  while (*s) {
    while (*s && isSpace(*s)) ++s;
    if (!*s) break;
    const char* b = s;
    while (*s && !isSpace(*s)) ++s;
    if (!f(Token{b, static_cast<std::size_t>(s - b)})) return;
  }
}

// A non-negative decimal integer of at most 18 digits (no sign, no spaces), as COLLADA's
// uint and int index lists write them.
bool parseUint(const Token& t, std::uint64_t* out) {
  if (t.n == 0 || t.n > 18) return false;
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < t.n; ++i) {
    const char c = t.b[i];
    if (c < '0' || c > '9') return false;
    v = v * 10 + static_cast<std::uint64_t>(c - '0');
  }
  *out = v;
  return true;
}
bool parseUint(const std::string& s, std::uint64_t* out) { return parseUint(Token{s.data(), s.size()}, out); }

// strtod stops at the whitespace that ends the token; the whole token must be the number.
bool parseNumber(const Token& t) {
  char* end = nullptr;
  std::strtod(t.b, &end);
  return end == t.b + t.n;
}

std::string quoted(const char* s) { return std::string("'") + (s ? s : "") + "'"; }

// The element as the message names it: its tag and the attribute that tells it apart.
std::string describe(const XMLElement* e) {
  std::string out = std::string("<") + e->Name();
  for (const char* a : {"id", "name", "source", "url", "semantic"}) {
    if (const char* v = e->Attribute(a)) {
      std::string value = v;
      if (value.size() > 60) value = value.substr(0, 60) + "...";
      out += std::string(" ") + a + "='" + value + "'";
      break;
    }
  }
  return out + ">";
}

// Saturating sums for the limits (a node instanced 2^40 times must not wrap).
double satAdd(double a, double b) { return std::min(a + b, 1e300); }

struct DataArray {
  const XMLElement* e = nullptr;
  std::uint64_t values = 0;  // what assimp stores: `count` values
  bool is_float = false;
};

struct Channel {
  const XMLElement* e = nullptr;
  std::string semantic;
  std::string source;  // without '#'
  std::uint64_t offset = 0;
};

class ColladaCheck {
 public:
  explicit ColladaCheck(std::string path) : path_(std::move(path)) {}

  void run(tinyxml2::XMLDocument& doc) {
    const tinyxml2::XMLError err = doc.LoadFile(path_.c_str());
    if (err != tinyxml2::XML_SUCCESS) {
      // assimp's pugixml reads what tinyxml2 refuses only in corner cases (tinyxml2 stops at
      // 100 nested elements); what is not checked is not passed on.
      throw MeshError("mesh '" + path_ + "': unreadable (line " + std::to_string(doc.ErrorLineNum()) +
                      ": malformed XML, " + std::string(doc.ErrorName()) + ")");
    }
    // assimp looks for <COLLADA> anywhere in the document (XmlParser::findNode), and its
    // libraries are keyed by id across the whole file: every element is checked where it is.
    collect(doc.RootElement());
    for (const XMLElement* g : geometries_) checkGeometry(g);
    checkNodes();
  }

 private:
  [[noreturn]] void fail(const XMLElement* e, const std::string& what) const {
    throw MeshError(formatLocation(path_, e ? e->GetLineNum() : 0) + "COLLADA " +
                    (e ? describe(e) + ": " : std::string()) + what);
  }

  // An unsigned attribute: its value, `fallback` when absent; an error when it is not a
  // non-negative integer <= max.
  std::uint64_t uintAttr(const XMLElement* e, const char* name, std::uint64_t fallback,
                         std::uint64_t max) const {
    const char* v = e->Attribute(name);
    if (!v) return fallback;
    std::uint64_t out = 0;
    if (!parseUint(v, &out))
      fail(e, std::string(name) + " " + quoted(v) + " is not a non-negative integer");
    if (out > max)
      fail(e, std::string(name) + " " + std::to_string(out) + " is above the limit of " + std::to_string(max));
    return out;
  }

  // Every element of the document, pre-order: the libraries assimp keys by id.
  void collect(const XMLElement* root) {
    std::vector<const XMLElement*> stack;
    if (root) stack.push_back(root);
    while (!stack.empty()) {
      const XMLElement* e = stack.back();
      stack.pop_back();
      const std::string name = e->Name();
      const char* id = e->Attribute("id");
      if (name == "float_array" || name == "Name_array" || name == "IDREF_array") {
        readArray(e, name == "float_array");
      } else if (name == "source") {
        readSource(e);
      } else if (name == "geometry") {
        geometries_.push_back(e);
        // ColladaParser::ReadGeometryLibrary keeps the first geometry of an id.
        if (id) geometry_by_id_.emplace(id, e);
      } else if (name == "controller") {
        if (id) controller_by_id_[id] = e;
      } else if (name == "node" || name == "visual_scene") {
        if (id) nodes_by_ref_.emplace(id, e);
        if (const char* n = e->Attribute("name")) nodes_by_ref_.emplace(n, e);
        if (name == "visual_scene") scenes_.push_back(e);
      }
      std::vector<const XMLElement*> children;
      for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) children.push_back(c);
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
    }
  }

  // ColladaParser::ReadDataArray reserves `count` values, then reads that many (and throws
  // when the text holds fewer): a count far above the text is an allocation without bound.
  void readArray(const XMLElement* e, bool is_float) {
    const std::uint64_t count = uintAttr(e, "count", 0, kMaxFileBytes);
    std::uint64_t n = 0;
    std::string bad;
    forEachToken(textOf(e), [&](const Token& t) {
      if (is_float && !parseNumber(t)) {
        bad = t.str();
        return false;
      }
      ++n;
      return true;
    });
    if (!bad.empty()) fail(e, "value " + quoted(bad.substr(0, 40).c_str()) + " is not a number");
    if (count > n)
      fail(e, "count " + std::to_string(count) + " but it holds " + std::to_string(n) + " values");
    DataArray a;
    a.e = e;
    a.values = count;
    a.is_float = is_float;
    if (const char* id = e->Attribute("id")) arrays_[id] = a;  // later ones replace, as in assimp
  }

  // ColladaParser::ReadSource: the accessor of each <technique_common> in the <source>, stored
  // under the source's id (the last one wins).
  void readSource(const XMLElement* e) {
    const char* id = e->Attribute("id");
    if (!id) return;
    std::vector<const XMLElement*> stack{e};
    while (!stack.empty()) {
      const XMLElement* x = stack.back();
      stack.pop_back();
      if (std::strcmp(x->Name(), "technique_common") == 0) {
        if (const XMLElement* acc = x->FirstChildElement("accessor")) accessors_[id] = acc;
      }
      for (const XMLElement* c = x->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
    }
  }

  // The number of objects the source `id` can be indexed with. ColladaParser's
  // ExtractDataObjectFromChannel checks an index against the accessor's count only, then reads
  // values[offset + index * stride + sub-offset] of the array: the accessor must stay inside
  // the array (a zero count, a huge stride or offset, a count above the array: out of bounds).
  std::uint64_t objectsOf(const XMLElement* input, const std::string& id) {
    const auto memo = object_count_.find(id);
    if (memo != object_count_.end()) return memo->second;
    const auto it = accessors_.find(id);
    if (it == accessors_.end()) fail(input, "source '#" + id + "' names no <source> with an <accessor>");
    const XMLElement* acc = it->second;
    const char* src = acc->Attribute("source");
    if (!src || src[0] != '#') fail(acc, std::string("source ") + quoted(src) + " is not '#<array id>'");
    const auto arr = arrays_.find(src + 1);
    if (arr == arrays_.end() || !arr->second.is_float)
      fail(acc, std::string("source ") + quoted(src) + " names no <float_array>");
    const std::uint64_t values = arr->second.values;
    // assimp reads count as an int: a negative one would be a huge size_t.
    const std::uint64_t count = uintAttr(acc, "count", 0, kMaxFileBytes);
    const std::uint64_t offset = uintAttr(acc, "offset", 0, kMaxFileBytes);
    const std::uint64_t stride = uintAttr(acc, "stride", 1, kMaxFileBytes);
    std::uint64_t params = 0;
    std::vector<const XMLElement*> stack{acc};
    while (!stack.empty()) {
      const XMLElement* x = stack.back();
      stack.pop_back();
      if (x != acc && std::strcmp(x->Name(), "param") == 0) ++params;
      for (const XMLElement* c = x->FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
    }
    if (count > 0) {
      if (stride == 0) fail(acc, "stride 0: every object would be the first (COLLADA: stride >= 1)");
      // All three are below 2^28 here, so the sum cannot wrap.
      const std::uint64_t last = offset + (count - 1) * stride + (params > 0 ? params - 1 : 0);
      if (last >= values)
        fail(acc, "count " + std::to_string(count) + ", stride " + std::to_string(stride) + ", offset " +
                      std::to_string(offset) + " and " + std::to_string(params) +
                      " params read past the end of " + describe(arr->second.e) + " (line " +
                      std::to_string(arr->second.e->GetLineNum()) + ", " + std::to_string(values) +
                      " values)");
    }
    object_count_[id] = count;
    return count;
  }

  Channel channelOf(const XMLElement* input) const {
    Channel c;
    c.e = input;
    const char* semantic = input->Attribute("semantic");
    c.semantic = semantic ? semantic : "";
    const char* src = input->Attribute("source");
    if (!src || src[0] != '#') fail(input, std::string("source ") + quoted(src) + " is not '#<id>'");
    c.source = src + 1;
    // assimp keeps offsets up to max + 1 per vertex: an offset of 4e9 would make every
    // vertex 4e9 indices long.
    c.offset = uintAttr(input, "offset", 0, 255);
    return c;
  }

  // ColladaParser::GetTypeForSemantic: other semantics are dropped, offsets and all.
  static bool knownSemantic(const std::string& s) {
    static const char* const kKnown[] = {"POSITION", "TEXCOORD",    "NORMAL",  "COLOR",     "VERTEX",
                                         "BINORMAL", "TEXBINORMAL", "TANGENT", "TEXTANGENT"};
    return std::any_of(std::begin(kKnown), std::end(kKnown), [&](const char* k) { return s == k; });
  }

  // ColladaParser::ReadMesh reads every <source>, <vertices> and primitive element under the
  // <mesh>, pre-order.
  void checkGeometry(const XMLElement* geometry) {
    double triangles = 0;
    for (const XMLElement* mesh = geometry->FirstChildElement("mesh"); mesh;
         mesh = mesh->NextSiblingElement("mesh")) {
      std::vector<const XMLElement*> order;
      std::vector<const XMLElement*> stack{mesh};
      while (!stack.empty()) {
        const XMLElement* x = stack.back();
        stack.pop_back();
        if (x != mesh) order.push_back(x);
        for (const XMLElement* c = x->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
      }
      std::string vertices_id;
      std::vector<Channel> per_vertex;
      for (const XMLElement* x : order) {
        const std::string name = x->Name();
        if (name == "vertices") {
          const char* id = x->Attribute("id");
          vertices_id = id ? id : "";
          for (const XMLElement* in = x->FirstChildElement("input"); in; in = in->NextSiblingElement("input")) {
            Channel c = channelOf(in);
            if (knownSemantic(c.semantic)) per_vertex.push_back(c);
          }
        } else if (name == "triangles" || name == "lines" || name == "linestrips" || name == "polygons" ||
                   name == "polylist" || name == "trifans" || name == "tristrips") {
          triangles = satAdd(triangles, checkPrimitives(x, name, vertices_id, per_vertex));
        }
      }
    }
    if (const char* id = geometry->Attribute("id")) {
      if (geometry_by_id_.find(id)->second == geometry) geometry_triangles_[id] = triangles;
    }
  }

  // One primitive element (ColladaParser::ReadIndexData and ReadPrimitives). Returns the
  // triangles it makes.
  double checkPrimitives(const XMLElement* prim, const std::string& kind, const std::string& vertices_id,
                         const std::vector<Channel>& per_vertex) {
    const std::uint64_t count = uintAttr(prim, "count", 0, kMaxTriangles);
    std::vector<Channel> channels;
    std::vector<const XMLElement*> vcounts, ps;
    std::vector<const XMLElement*> stack{prim};
    while (!stack.empty()) {
      const XMLElement* x = stack.back();
      stack.pop_back();
      if (x != prim) {
        const std::string name = x->Name();
        if (name == "input") {
          Channel c = channelOf(x);
          if (knownSemantic(c.semantic)) channels.push_back(c);
        } else if (name == "vcount") {
          vcounts.push_back(x);
        } else if (name == "p") {
          ps.push_back(x);
        }
      }
      for (const XMLElement* c = x->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
    }
    const bool fixed_list = kind == "triangles" || kind == "lines" || kind == "polylist";
    // Each <p> of these is one primitive; assimp asserts that there are `count` of them
    // (polygons) or makes a strip of -2 triangles of an empty one.
    if (!fixed_list && ps.size() != count)
      fail(prim, "count " + std::to_string(count) + " but " + std::to_string(ps.size()) +
                     " <p> elements (one per " + (kind == "polygons" ? "polygon" : "strip or fan") + ")");
    if (count == 0) return 0;  // assimp reads no index of these
    if (fixed_list && ps.size() != 1)
      fail(prim, "count " + std::to_string(count) + " but " + std::to_string(ps.size()) +
                     " <p> elements (COLLADA gives one list)");

    // The slots of each vertex: max offset + 1, each with the number of objects its index reads.
    std::uint64_t slots = 1;
    for (const Channel& c : channels) slots = std::max(slots, c.offset + 1);
    std::vector<std::uint64_t> bound(slots, ~0ull);
    bool has_vertex = false;
    for (const Channel& c : channels) {
      std::uint64_t n = 0;
      if (c.semantic == "VERTEX") {
        // ReadPrimitives: the VERTEX input must name this mesh's <vertices>, whose inputs are
        // each indexed with it; without a POSITION among them assimp copies positions that
        // were never read (ColladaLoader::CreateMesh).
        if (c.source != vertices_id)
          fail(c.e, "source '#" + c.source + "' is not this mesh's <vertices> ('#" + vertices_id + "')");
        bool position = false;
        n = ~0ull;
        for (const Channel& v : per_vertex) {
          if (v.semantic == "VERTEX") continue;
          n = std::min(n, objectsOf(v.e, v.source));
          position = position || v.semantic == "POSITION";
        }
        if (!position) fail(c.e, "its <vertices> '#" + vertices_id + "' has no POSITION input");
        has_vertex = true;
      } else {
        n = objectsOf(c.e, c.source);
      }
      bound[c.offset] = std::min(bound[c.offset], n);
    }
    // Without one, assimp reads index -1 of every vertex (ColladaParser::CopyVertex).
    if (!has_vertex) fail(prim, "has no VERTEX input");

    std::vector<std::uint64_t> vcount;
    if (kind == "polylist") {
      if (vcounts.size() != 1)
        fail(prim, "count " + std::to_string(count) + " but " + std::to_string(vcounts.size()) +
                       " <vcount> elements (a polylist gives one)");
      std::string bad;
      forEachToken(textOf(vcounts[0]), [&](const Token& t) {
        std::uint64_t v = 0;
        if (!parseUint(t, &v) || v == 0 || v > kMaxVertices) {
          bad = t.str();
          return false;
        }
        vcount.push_back(v);
        return vcount.size() < count;
      });
      if (!bad.empty())
        fail(vcounts[0], "entry " + quoted(bad.substr(0, 40).c_str()) + " is not a vertex count (1.." +
                             std::to_string(kMaxVertices) + ")");
      if (vcount.size() < count)
        fail(vcounts[0], "holds " + std::to_string(vcount.size()) + " entries for count " + std::to_string(count));
    }

    double triangles = 0;
    for (const XMLElement* p : ps) {
      std::uint64_t i = 0;
      std::string bad;
      bool out_of_range = false;
      std::uint64_t bad_value = 0, bad_bound = 0;
      forEachToken(textOf(p), [&](const Token& t) {
        std::uint64_t v = 0;
        if (!parseUint(t, &v)) {
          bad = t.str();
          return false;
        }
        const std::uint64_t b = bound[i % slots];
        if (v >= b) {
          out_of_range = true;
          bad_value = v;
          bad_bound = b;
          return false;
        }
        ++i;
        return i <= kMaxVertices * slots;
      });
      if (!bad.empty())
        fail(p, "index " + quoted(bad.substr(0, 40).c_str()) + " (number " + std::to_string(i + 1) +
                    ") is not a non-negative integer");
      if (out_of_range) {
        fail(p, "index " + std::to_string(bad_value) + " (number " + std::to_string(i + 1) + ", offset " +
                    std::to_string(i % slots) + ") is out of range: its input has " + std::to_string(bad_bound) +
                    " elements");
      }
      if (i > kMaxVertices * slots)
        fail(p, "more than " + std::to_string(kMaxVertices) + " vertices (the limit)");
      if (i % slots != 0)
        fail(p, std::to_string(i) + " indices are not a whole number of vertices of " + std::to_string(slots) +
                    " indices (the inputs' offsets)");
      const std::uint64_t n = i / slots;
      if (kind == "triangles") {
        if (n != 3 * count)
          fail(p, "holds " + std::to_string(n) + " vertices; count " + std::to_string(count) +
                      " triangles need " + std::to_string(3 * count));
        triangles = satAdd(triangles, static_cast<double>(count));
      } else if (kind == "polylist") {
        std::uint64_t sum = 0;
        for (std::uint64_t v : vcount) {
          sum += v;
          if (v >= 3) triangles = satAdd(triangles, static_cast<double>(v - 2));
        }
        if (n != sum)
          fail(p, "holds " + std::to_string(n) + " vertices; the <vcount> entries add up to " + std::to_string(sum));
      } else if (kind == "lines") {
        // assimp mends a wrong count of lines (SketchUp writes them so); lines are dropped.
      } else {
        const std::uint64_t min = kind == "linestrips" ? 2 : 3;
        if (n < min)
          fail(p, "holds " + std::to_string(n) + " vertices; a " + kind.substr(0, kind.size() - 1) + " needs " +
                      std::to_string(min));
        if (kind != "linestrips") triangles = satAdd(triangles, static_cast<double>(n - 2));
      }
    }
    if (triangles > static_cast<double>(kMaxTriangles))
      fail(prim, "more than " + std::to_string(kMaxTriangles) + " triangles (the limit)");
    return triangles;
  }

  // The node graph assimp builds (ColladaLoader::BuildHierarchy): each node's child nodes and
  // the nodes its <instance_node>s name, followed recursively. A cycle recurses until the
  // stack overflows; a chain of instances of instances multiplies. Checked depth first with a
  // visited set, with the instanced nodes and triangles summed.
  struct Cost {
    double nodes = 0;
    double triangles = 0;
  };

  std::vector<const XMLElement*> targetsOf(const XMLElement* instance) const {
    std::vector<const XMLElement*> out;
    const char* url = instance->Attribute("url");
    if (!url || url[0] != '#') return out;  // assimp logs and ignores it
    // ResolveNodeInstances: the node library by id, else any scene node by name or id.
    const auto range = nodes_by_ref_.equal_range(url + 1);
    for (auto it = range.first; it != range.second; ++it) {
      if (std::find(out.begin(), out.end(), it->second) == out.end()) out.push_back(it->second);
    }
    return out;
  }

  double geometryTriangles(const XMLElement* instance) const {
    const char* url = instance->Attribute("url");
    if (!url || url[0] != '#') return 0;
    std::string id = url + 1;
    if (std::strcmp(instance->Name(), "instance_controller") == 0) {
      // The loader reads the skin's or morph's source mesh in its place (mesh.cpp).
      const auto c = controller_by_id_.find(id);
      const XMLElement* skin = nullptr;
      if (c != controller_by_id_.end()) {
        skin = c->second->FirstChildElement("skin");
        if (!skin) skin = c->second->FirstChildElement("morph");
      }
      const char* src = skin ? skin->Attribute("source") : nullptr;
      if (!src || src[0] != '#') return 0;
      id = src + 1;
    }
    const auto g = geometry_triangles_.find(id);
    return g == geometry_triangles_.end() ? 0 : g->second;
  }

  Cost visit(const XMLElement* node, const XMLElement* via, int depth) {
    const auto done = cost_.find(node);
    if (done != cost_.end()) return done->second;
    if (depth > kMaxNodeDepth)
      fail(via ? via : node, "nodes nest deeper than " + std::to_string(kMaxNodeDepth) + " (the limit)");
    on_path_.push_back(node);
    Cost c;
    c.nodes = 1;
    for (const XMLElement* x = node->FirstChildElement(); x; x = x->NextSiblingElement()) {
      const std::string name = x->Name();
      std::vector<const XMLElement*> next;
      if (name == "node") {
        next.push_back(x);
      } else if (name == "instance_node") {
        next = targetsOf(x);
      } else if (name == "instance_geometry" || name == "instance_controller") {
        c.triangles = satAdd(c.triangles, geometryTriangles(x));
        continue;
      } else {
        continue;
      }
      for (const XMLElement* n : next) {
        const auto cycle = std::find(on_path_.begin(), on_path_.end(), n);
        if (cycle != on_path_.end()) {
          std::string path;
          for (auto it = cycle; it != on_path_.end(); ++it) path += nameOf(*it) + " -> ";
          fail(x, "instances a node inside itself (" + path + nameOf(n) + "): a node cycle");
        }
        const Cost sub = visit(n, x, depth + 1);
        c.nodes = satAdd(c.nodes, sub.nodes);
        c.triangles = satAdd(c.triangles, sub.triangles);
      }
      if (c.nodes > static_cast<double>(kMaxNodes))
        fail(x, "the scene expands to more than " + std::to_string(kMaxNodes) + " nodes (the limit)");
      if (c.triangles > static_cast<double>(kMaxTriangles))
        fail(x, "the scene places more than " + std::to_string(kMaxTriangles) + " triangles (the limit)");
    }
    on_path_.pop_back();
    cost_[node] = c;
    return c;
  }

  static std::string nameOf(const XMLElement* e) {
    const char* id = e->Attribute("id");
    const char* name = e->Attribute("name");
    return "'" + std::string(id ? id : name ? name : e->Name()) + "'";
  }

  void checkNodes() {
    for (const XMLElement* scene : scenes_) visit(scene, nullptr, 0);
  }

  std::string path_;
  std::map<std::string, DataArray> arrays_;
  std::map<std::string, const XMLElement*> accessors_;
  std::map<std::string, std::uint64_t> object_count_;
  std::vector<const XMLElement*> geometries_;
  std::map<std::string, const XMLElement*> geometry_by_id_;
  std::map<std::string, double> geometry_triangles_;
  std::map<std::string, const XMLElement*> controller_by_id_;
  std::multimap<std::string, const XMLElement*> nodes_by_ref_;
  std::vector<const XMLElement*> scenes_;
  std::map<const XMLElement*, Cost> cost_;
  std::vector<const XMLElement*> on_path_;
};

}  // namespace

void checkCollada(const std::string& path, tinyxml2::XMLDocument* doc) { ColladaCheck(path).run(*doc); }

namespace {

struct SceneCheck {
  const std::string& path;
  const aiScene* scene;
  double placed_triangles = 0;
  double placed_vertices = 0;
  std::uint64_t nodes = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw MeshError("mesh '" + path + "': " + what + " (assimp's result; the file is malformed)");
  }

  // Faces: 1..3 indices after aiProcess_Triangulate, each < mNumVertices. Returns triangles.
  std::uint64_t checkMesh(unsigned m) const {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!mesh) fail("mesh " + std::to_string(m) + " is missing");
    if (mesh->mNumVertices > kMaxVertices)
      fail("mesh " + std::to_string(m) + " has " + std::to_string(mesh->mNumVertices) + " vertices (limit " +
           std::to_string(kMaxVertices) + ")");
    if (mesh->mNumVertices > 0 && !mesh->mVertices) fail("mesh " + std::to_string(m) + " has no vertex array");
    if (mesh->mNumFaces > 0 && !mesh->mFaces) fail("mesh " + std::to_string(m) + " has no face array");
    std::uint64_t triangles = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || face.mNumIndices > 3 || !face.mIndices)
        fail("mesh " + std::to_string(m) + " face " + std::to_string(f) + " has " +
             std::to_string(face.mNumIndices) + " corners");
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices)
          fail("mesh " + std::to_string(m) + " face " + std::to_string(f) + " uses vertex " +
               std::to_string(face.mIndices[k]) + " of " + std::to_string(mesh->mNumVertices));
      }
      if (face.mNumIndices == 3) ++triangles;
    }
    return triangles;
  }

  void visit(const aiNode* node, int depth, const std::vector<std::uint64_t>& triangles) {
    if (!node) fail("a node is missing");
    if (depth > kMaxNodeDepth) fail("nodes nest deeper than " + std::to_string(kMaxNodeDepth));
    if (++nodes > kMaxNodes) fail("more than " + std::to_string(kMaxNodes) + " nodes");
    if (node->mNumMeshes > 0 && !node->mMeshes) fail("node '" + std::string(node->mName.C_Str()) + "' lost its meshes");
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      if (node->mMeshes[i] >= scene->mNumMeshes)
        fail("node '" + std::string(node->mName.C_Str()) + "' names mesh " + std::to_string(node->mMeshes[i]) +
             " of " + std::to_string(scene->mNumMeshes));
      placed_triangles += static_cast<double>(triangles[node->mMeshes[i]]);
      placed_vertices += static_cast<double>(scene->mMeshes[node->mMeshes[i]]->mNumVertices);
    }
    if (placed_triangles > static_cast<double>(kMaxTriangles))
      fail("more than " + std::to_string(kMaxTriangles) + " triangles placed (the limit)");
    // The placed vertices are indexed with uint32 (TriangleMesh::indices).
    if (placed_vertices > 3.0 * static_cast<double>(kMaxTriangles))
      fail("more than " + std::to_string(3 * kMaxTriangles) + " vertices placed (the limit)");
    if (node->mNumChildren > 0 && !node->mChildren) fail("node '" + std::string(node->mName.C_Str()) + "' lost its children");
    for (unsigned c = 0; c < node->mNumChildren; ++c) visit(node->mChildren[c], depth + 1, triangles);
  }
};

}  // namespace

void checkScene(const std::string& path, const aiScene* scene) {
  SceneCheck check{path, scene};
  if (scene->mNumMeshes > 0 && !scene->mMeshes) check.fail("the mesh list is missing");
  std::vector<std::uint64_t> triangles(scene->mNumMeshes);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) triangles[m] = check.checkMesh(m);
  check.visit(scene->mRootNode, 0, triangles);
}

}  // namespace mesh_check
}  // namespace tianracer_assets
