#include "keyturn/sim/mesh.h"


#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/error.h"
#include "keyturn/core/ply_reader.h"

namespace keyturn::sim {

Eigen::Vector3f Mesh::boundsMin() const {
  Eigen::Vector3f m = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  for (const auto& v : vertices) m = m.cwiseMin(v);
  return m;
}

Eigen::Vector3f Mesh::boundsMax() const {
  Eigen::Vector3f m = Eigen::Vector3f::Constant(-std::numeric_limits<float>::infinity());
  for (const auto& v : vertices) m = m.cwiseMax(v);
  return m;
}

namespace {

// PLY through keyturn's bounds-checked reader: vertex x/y/z and a face list
// ("vertex_indices" or "vertex_index"); polygons are fan-triangulated.
Mesh loadPly(const std::string& path) {
  const PlyData ply = readPly(path);
  const PlyElement* vertex = ply.find("vertex");
  if (!vertex) throw Error(path + ": PLY mesh has no vertex element");
  const PlyProperty* x = vertex->find("x");
  const PlyProperty* y = vertex->find("y");
  const PlyProperty* z = vertex->find("z");
  if (!x || !y || !z || x->is_list || y->is_list || z->is_list) throw Error(path + ": PLY mesh has no x/y/z");
  Mesh mesh;
  for (std::size_t i = 0; i < vertex->count; ++i)
    mesh.vertices.emplace_back(Eigen::Vector3d(x->values[i], y->values[i], z->values[i]).cast<float>());
  const PlyElement* face = ply.find("face");
  if (!face) return mesh;
  const PlyProperty* idx = face->find("vertex_indices");
  if (!idx) idx = face->find("vertex_index");
  if (!idx || !idx->is_list) throw Error(path + ": PLY face element has no vertex_indices list");
  const int last = static_cast<int>(mesh.vertices.size()) - 1;
  std::vector<int> corner;
  for (std::size_t f = 0; f < face->count; ++f) {
    const double* v = idx->values.data() + idx->offsets[f];
    const std::size_t len = idx->offsets[f + 1] - idx->offsets[f];
    corner.clear();
    // Checked as doubles: a float-typed list may hold NaN, fractions or 1e30.
    for (std::size_t k = 0; k < len; ++k) {
      const auto i = integerIn(v[k], 0, last);
      if (!i)
        throw Error(path + ": face " + std::to_string(f) + " refers to vertex " + numberText(v[k]) +
                    ", not a vertex index in 0.." + std::to_string(last));
      corner.push_back(*i);
    }
    for (std::size_t k = 2; k < len; ++k) mesh.triangles.emplace_back(corner[0], corner[k - 1], corner[k]);
  }
  return mesh;
}

// OFF ("Object File Format"): "OFF", then "V F E", V vertex lines, F faces "n i0 i1 …".
Mesh loadOff(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  auto next = [&](std::istringstream& ls) {
    while (std::getline(in, line)) {
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      ls.clear();
      ls.str(line);
      return true;
    }
    return false;
  };
  std::istringstream ls;
  std::string magic;
  if (!next(ls) || !(ls >> magic) || magic != "OFF") throw Error(path + ": not an OFF file (no OFF header)");
  long nv = 0, nf = 0;
  if (!(ls >> nv >> nf) && !(next(ls) && (ls >> nv >> nf)))
    throw Error(path + ": OFF header lacks vertex and face counts");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (nv < 0 || nf < 0 || static_cast<std::uintmax_t>(nv + nf) > size)
    throw Error(path + ": OFF header promises " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                " faces, more than the file can hold");
  Mesh mesh;
  for (long i = 0; i < nv; ++i) {
    float x, y, z;
    if (!next(ls) || !(ls >> x >> y >> z)) throw Error(path + ": OFF vertex " + std::to_string(i) + " unreadable");
    mesh.vertices.emplace_back(x, y, z);
  }
  for (long f = 0; f < nf; ++f) {
    int k = 0;
    if (!next(ls) || !(ls >> k) || k < 3) throw Error(path + ": OFF face " + std::to_string(f) + " unreadable");
    std::vector<int> idx(static_cast<std::size_t>(k));
    for (int& i : idx)
      if (!(ls >> i) || i < 0 || i >= nv)
        throw Error(path + ": OFF face " + std::to_string(f) + " refers to a missing vertex");
    for (int j = 2; j < k; ++j) mesh.triangles.emplace_back(idx[0], idx[j - 1], idx[j]);
  }
  return mesh;
}

// STL, binary (80-byte header, triangle count, 50-byte records) or ASCII
// ("vertex x y z" lines, three per facet). keyturn's own reader: VTK's guessed
// "binary" from any stray byte and allocated for the header's count unchecked,
// and grew without bound on fuzzed ASCII.
Mesh loadStl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Mesh mesh;
  auto addTriangle = [&](const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
    const int base = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(a);
    mesh.vertices.push_back(b);
    mesh.vertices.push_back(c);
    mesh.triangles.emplace_back(base, base + 1, base + 2);
  };
  std::uint32_t count = 0;
  if (text.size() >= 84) std::memcpy(&count, text.data() + 80, 4);
  if (text.size() >= 84 && 84ull + 50ull * count == text.size()) {
    for (std::uint32_t t = 0; t < count; ++t) {
      float f[9];
      std::memcpy(f, text.data() + 84 + 50ull * t + 12, sizeof f);  // skip the normal
      addTriangle({f[0], f[1], f[2]}, {f[3], f[4], f[5]}, {f[6], f[7], f[8]});
    }
    return mesh;
  }
  if (text.compare(0, 5, "solid") != 0)
    throw Error(path + ": not a valid STL (neither ASCII 'solid …' text nor a binary STL whose size matches its "
                       "triangle count)");
  std::istringstream ss(text);
  std::vector<Eigen::Vector3f> corner;
  std::string line;
  for (int n = 1; std::getline(ss, line); ++n) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key != "vertex") continue;
    float x, y, z;
    if (!(ls >> x >> y >> z)) throw Error(path + ": line " + std::to_string(n) + ": a vertex needs x y z");
    corner.emplace_back(x, y, z);
    if (corner.size() == 3) {
      addTriangle(corner[0], corner[1], corner[2]);
      corner.clear();
    }
  }
  if (!corner.empty()) throw Error(path + ": a facet ends with " + std::to_string(corner.size()) + " vertices");
  return mesh;
}

// OBJ: "v x y z [w]" and "f a b c …" with a, a/t, a/t/n or a//n (1-based, or
// negative from the end). keyturn's own parser: PCL's OBJReader reads vertex
// coordinates without checking they are there (a fuzzed "v 0 0" crashed it).
Mesh loadObj(const std::string& path) {
  std::ifstream in(path);
  Mesh mesh;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    const std::string where = path + ": line " + std::to_string(n) + ": ";
    if (key == "v") {
      float x, y, z;
      if (!(ls >> x >> y >> z)) throw Error(where + "a vertex needs x y z");
      mesh.vertices.emplace_back(x, y, z);
    } else if (key == "f") {
      std::vector<int> idx;
      for (std::string tok; ls >> tok;) {
        int i = 0;
        try {
          std::size_t used = 0;
          i = std::stoi(tok, &used);
          if (used != tok.size() && tok[used] != '/') throw std::invalid_argument(tok);
        } catch (const std::exception&) {
          throw Error(where + "bad face index '" + tok.substr(0, 20) + "'");
        }
        const int nv = static_cast<int>(mesh.vertices.size());
        const int v = i > 0 ? i - 1 : nv + i;
        if (i == 0 || v < 0 || v >= nv) throw Error(where + "face refers to a missing vertex " + std::to_string(i));
        idx.push_back(v);
      }
      if (idx.size() < 3) throw Error(where + "a face needs at least 3 vertices");
      for (std::size_t k = 2; k < idx.size(); ++k) mesh.triangles.emplace_back(idx[0], idx[k - 1], idx[k]);
    }
  }
  return mesh;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

Mesh loadMesh(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": no such mesh file");
  if (std::filesystem::file_size(path, ec) == 0) throw Error(path + ": empty file (0 bytes)");
  const std::string ext = lowerExtension(path);
  Mesh mesh;
  if (ext == ".ply") {
    mesh = loadPly(path);
  } else if (ext == ".obj") {
    mesh = loadObj(path);
  } else if (ext == ".stl") {
    mesh = loadStl(path);
  } else if (ext == ".off") {
    mesh = loadOff(path);
  } else {
    throw Error(path + ": unsupported mesh format '" + ext + "' (expected .ply, .obj, .stl or .off)");
  }
  if (mesh.triangles.empty()) throw Error(path + ": mesh has no faces");
  for (const auto& v : mesh.vertices)
    if (!v.allFinite()) throw Error(path + ": mesh has non-finite vertex coordinates");
  return mesh;
}

Mesh makeSphereTargetMesh(double radius, double offset) {
  Mesh m;
  const int rings = 24, segs = 48;
  const Eigen::Vector3f c(static_cast<float>(offset), 0.f, static_cast<float>(radius));
  for (int i = 0; i <= rings; ++i) {
    const double th = M_PI * i / rings;
    for (int j = 0; j < segs; ++j) {
      const double ph = 2 * M_PI * j / segs;
      m.vertices.push_back(c + static_cast<float>(radius) * Eigen::Vector3f(static_cast<float>(std::sin(th) * std::cos(ph)),
                                                                          static_cast<float>(std::sin(th) * std::sin(ph)),
                                                                          static_cast<float>(std::cos(th))));
    }
  }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segs; ++j) {
      const int a = i * segs + j, b = i * segs + (j + 1) % segs, cidx = a + segs, d = b + segs;
      m.triangles.emplace_back(a, cidx, d);
      m.triangles.emplace_back(a, d, b);
    }
  return m;
}

Mesh loadMeshOrBuiltin(const std::string& name) {
  if (name == "builtin:mug") return makeMugMesh();
  if (name == "builtin:sphere-target") return makeSphereTargetMesh();
  if (name.rfind("builtin:", 0) == 0) throw Error(name + ": unknown built-in mesh (builtin:mug, builtin:sphere-target)");
  return loadMesh(name);
}

Mesh scaledMesh(Mesh mesh, double factor) {
  const float f = static_cast<float>(factor);
  for (auto& v : mesh.vertices) v *= f;
  return mesh;
}

Mesh makeMugMesh() {
  Mesh m;
  const int seg = 48;
  const float r_out = 0.040f, r_in = 0.036f, h = 0.10f, floor_z = 0.006f;
  auto ring = [&](float r, float z) {
    const int base = static_cast<int>(m.vertices.size());
    for (int i = 0; i < seg; ++i) {
      const float a = 2.f * static_cast<float>(M_PI) * i / seg;
      m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
    return base;
  };
  auto strip = [&](int a, int b, bool flip) {
    for (int i = 0; i < seg; ++i) {
      const int j = (i + 1) % seg;
      if (flip) {
        m.triangles.emplace_back(a + i, b + j, b + i);
        m.triangles.emplace_back(a + i, a + j, b + j);
      } else {
        m.triangles.emplace_back(a + i, b + i, b + j);
        m.triangles.emplace_back(a + i, b + j, a + j);
      }
    }
  };
  auto cap = [&](int ringBase, float z, bool up) {
    const int c = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(0.f, 0.f, z);
    for (int i = 0; i < seg; ++i) {
      const int j = (i + 1) % seg;
      if (up) m.triangles.emplace_back(c, ringBase + i, ringBase + j);
      else m.triangles.emplace_back(c, ringBase + j, ringBase + i);
    }
  };
  const int o0 = ring(r_out, 0.f), o1 = ring(r_out, h);
  const int i1 = ring(r_in, h), i0 = ring(r_in, floor_z);
  strip(o0, o1, false);  // outer wall
  strip(o1, i1, false);  // rim
  strip(i1, i0, false);  // inner wall
  cap(o0, 0.f, false);   // bottom
  cap(i0, floor_z, true);
  // Handle: half a torus on the +x side, tube radius 6 mm, centre-line radius 28 mm.
  const int tseg = 16, hseg = 24;
  const float R = 0.028f, tube = 0.006f;
  const Eigen::Vector3f centre(r_out - 0.004f, 0.f, h * 0.5f);
  const int base = static_cast<int>(m.vertices.size());
  for (int i = 0; i <= hseg; ++i) {
    const float a = -static_cast<float>(M_PI) / 2 + static_cast<float>(M_PI) * i / hseg;
    const Eigen::Vector3f c = centre + Eigen::Vector3f(R * std::cos(a), 0.f, R * std::sin(a));
    const Eigen::Vector3f radial(std::cos(a), 0.f, std::sin(a));
    for (int j = 0; j < tseg; ++j) {
      const float b = 2.f * static_cast<float>(M_PI) * j / tseg;
      m.vertices.push_back(c + tube * (std::cos(b) * radial + std::sin(b) * Eigen::Vector3f::UnitY()));
    }
  }
  for (int i = 0; i < hseg; ++i)
    for (int j = 0; j < tseg; ++j) {
      const int a = base + i * tseg + j, b = base + i * tseg + (j + 1) % tseg;
      m.triangles.emplace_back(a, a + tseg, b + tseg);
      m.triangles.emplace_back(a, b + tseg, b);
    }
  return m;
}

}  // namespace keyturn::sim
