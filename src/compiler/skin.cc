// Skins (MuJoCo's mjCSkin): triangle meshes drawn over bodies. A skin's data come inline
// or from a .skn file; the compiler checks their sizes, finds each bone's body and the
// material, normalizes each vertex's weights over its bones and each bind quaternion, and
// lays the skins out in the skin_* arrays. Skins do not take part in the physics.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "mjcf/assets.h"
#include "mjcf/error.h"

namespace simlab::compiler {

namespace {

// ---------------------------------------------------------------- .skn files

// Reads 4-byte words from a .skn file's bytes, failing at the file's end.
class SknReader {
 public:
  SknReader(const mjcf::SkinSpec& skin, const std::string& bytes) : skin_(skin), bytes_(bytes) {}

  // The number of 4-byte words left.
  size_t WordsLeft() const { return (bytes_.size() - at_) / 4; }

  int32_t Int() {
    int32_t v;
    Take(&v, 4);
    return v;
  }
  float Float() {
    float v;
    Take(&v, 4);
    return v;
  }
  // A bone's body name: 40 bytes, ended by its first zero (at most 39 characters).
  std::string Name() {
    char text[40];
    Take(text, 40);
    text[39] = '\0';
    return std::string(text);
  }
  [[noreturn]] void Fail(const std::string& what) const {
    ThrowAt(skin_.src, what + " in SKN file '" + skin_.path + "'");
  }

 private:
  void Take(void* out, size_t n) {
    if (bytes_.size() - at_ < n) Fail("insufficient data");
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }

  const mjcf::SkinSpec& skin_;
  const std::string& bytes_;
  size_t at_ = 0;
};

// A .skn file: a header of four counts (vertices, texture coordinates, faces, bones),
// the vertices, coordinates and faces, then each bone: a 40-byte body name, bind
// position and quaternion, a vertex count, the vertex ids and their weights.
void ReadSkn(const std::string& bytes, mjcf::SkinSpec* skin) {
  SknReader in(*skin, bytes);
  if (bytes.empty()) in.Fail("empty file");
  if (bytes.size() < 16) in.Fail("missing header");
  int32_t nvert = in.Int(), ntexcoord = in.Int(), nface = in.Int(), nbone = in.Int();
  if (nvert < 0 || ntexcoord < 0 || nface < 0 || nbone < 0) in.Fail("negative size in header");
  uint64_t words = 3ull * nvert + 2ull * ntexcoord + 3ull * nface;
  if (in.WordsLeft() < words) in.Fail("insufficient data");
  skin->vertex.resize(3 * static_cast<size_t>(nvert));
  for (float& v : skin->vertex) v = in.Float();
  skin->texcoord.resize(2 * static_cast<size_t>(ntexcoord));
  for (float& v : skin->texcoord) v = in.Float();
  skin->face.resize(3 * static_cast<size_t>(nface));
  for (int& v : skin->face) v = in.Int();
  for (int32_t b = 0; b < nbone; b++) {
    std::string bone = "bone " + std::to_string(b);
    if (in.WordsLeft() < 18) in.Fail("insufficient data for " + bone);
    mjcf::SkinBoneSpec spec;
    spec.src = skin->src;
    spec.body = in.Name();
    for (float& v : spec.bindpos) v = in.Float();
    for (float& v : spec.bindquat) v = in.Float();
    int32_t count = in.Int();
    if (count < 1) in.Fail("vertex count must be positive for " + bone);
    if (in.WordsLeft() < 2ull * count) in.Fail("insufficient vertex data for " + bone);
    spec.vertid.resize(count);
    for (int& v : spec.vertid) v = in.Int();
    spec.vertweight.resize(count);
    for (float& v : spec.vertweight) v = in.Float();
    skin->bones.push_back(std::move(spec));
  }
  if (in.WordsLeft() != 0 || bytes.size() % 4) in.Fail("unexpected buffer size");
}

// ---------------------------------------------------------------- checks

// The skin's data, from its file when it names one (then nothing may be given inline).
mjcf::SkinSpec SkinData(const mjcf::SkinSpec& s, const mjcf::AssetFiles* assets) {
  mjcf::SkinSpec skin = s;
  if (s.file.empty()) return skin;
  if (!s.vertex.empty() || !s.texcoord.empty() || !s.face.empty() || !s.bones.empty()) {
    ThrowAt(s.src, "both skin data and file were specified: " + s.file);
  }
  size_t dot = s.file.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : s.file.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".skn") ThrowAt(s.src, "unknown skin file type: " + s.file);
  std::string bytes;
  if (!mjcf::ReadFileOrAsset(s.path, assets, &bytes)) {
    ThrowAt(s.src, "could not read SKN file '" + s.path + "'" + mjcf::NotAmongAssets(assets));
  }
  ReadSkn(bytes, &skin);
  return skin;
}

// The sizes MuJoCo requires of a skin's data.
void CheckSizes(const mjcf::SkinSpec& s) {
  if (s.vertex.empty() || s.face.empty() || s.bones.empty()) {
    ThrowAt(s.src, "missing data in skin");
  }
  if (s.vertex.size() % 3) ThrowAt(s.src, "vertex data must be a multiple of 3");
  if (!s.texcoord.empty() && s.texcoord.size() != 2 * s.vertex.size() / 3) {
    ThrowAt(s.src, "vertex and texcoord data have incompatible sizes");
  }
  if (s.face.size() % 3) ThrowAt(s.src, "face data must be a multiple of 3");
}

// Each vertex's weights over its bones sum to 1 (a vertex no bone carries is an error),
// in single precision as MuJoCo's; the bind quaternions are normalized.
void NormalizeBones(mjcf::SkinSpec* s) {
  size_t nvert = s->vertex.size() / 3;
  std::vector<float> total(nvert, 0.0f);
  for (const mjcf::SkinBoneSpec& b : s->bones) {
    if (b.vertweight.size() != b.vertid.size() || b.vertid.empty()) {
      ThrowAt(b.src, "vertid and vertweight must have the same non-zero size in skin");
    }
    for (size_t j = 0; j < b.vertid.size(); j++) {
      int v = b.vertid[j];
      if (v < 0 || static_cast<size_t>(v) >= nvert) {
        ThrowAt(b.src, "vertid " + std::to_string(v) + " out of range in skin");
      }
      total[v] += b.vertweight[j];
    }
  }
  for (size_t v = 0; v < nvert; v++) {
    if (total[v] <= kMinVal) {
      ThrowAt(s->src, "vertex " + std::to_string(v) + " must have positive total weight in skin");
    }
  }
  for (mjcf::SkinBoneSpec& b : s->bones) {
    for (size_t j = 0; j < b.vertid.size(); j++) b.vertweight[j] /= total[b.vertid[j]];
    double q[4] = {b.bindquat[0], b.bindquat[1], b.bindquat[2], b.bindquat[3]};
    NormalizeVec(q, 4);
    for (int k = 0; k < 4; k++) b.bindquat[k] = static_cast<float>(q[k]);
  }
}

}  // namespace

// ---------------------------------------------------------------- the section

void CompileSkins(const mjcf::ModelSpec& spec, CompileState* state) {
  NameIndex bodies = BodyNames(*state);
  NameIndex materials = MaterialNames(spec);
  state->skins.clear();
  for (const mjcf::SkinSpec& s : spec.skins) {
    SkinState skin;
    skin.data = SkinData(s, spec.assets.get());
    CheckSizes(skin.data);
    for (const mjcf::SkinBoneSpec& b : skin.data.bones) {
      int id = bodies.Find(b.body);
      if (id < 0) ThrowAt(b.src, "unknown body '" + b.body + "' in skin");
      skin.bodyid.push_back(id);
    }
    skin.matid = s.material.empty() ? -1 : materials.Find(s.material);
    if (!s.material.empty() && skin.matid < 0) {
      ThrowAt(s.src, "unknown material '" + s.material + "' in skin");
    }
    NormalizeBones(&skin.data);
    state->skins.push_back(std::move(skin));
  }
}

void SkinSizes(const CompileState& state, Model* m) {
  m->nskin = static_cast<int>(state.skins.size());
  m->nskinvert = m->nskintexvert = m->nskinface = m->nskinbone = m->nskinbonevert = 0;
  for (const SkinState& s : state.skins) {
    m->nskinvert += static_cast<int>(s.data.vertex.size() / 3);
    m->nskintexvert += static_cast<int>(s.data.texcoord.size() / 2);
    m->nskinface += static_cast<int>(s.data.face.size() / 3);
    m->nskinbone += static_cast<int>(s.data.bones.size());
    for (const mjcf::SkinBoneSpec& b : s.data.bones) {
      m->nskinbonevert += static_cast<int>(b.vertid.size());
    }
  }
}

void LayoutSkins(const CompileState& state, Model* m) {
  int vert = 0, texcoord = 0, face = 0, bone = 0, bonevert = 0;
  for (int i = 0; i < m->nskin; i++) {
    const SkinState& skin = state.skins[i];
    const mjcf::SkinSpec& s = skin.data;
    m->skin_names[i] = s.src.name;
    m->skin_matid[i] = skin.matid;
    m->skin_group[i] = s.group;
    for (int k = 0; k < 4; k++) m->skin_rgba[4 * i + k] = s.rgba[k];
    m->skin_inflate[i] = s.inflate;

    // The mesh: vertices, texture coordinates (or -1), faces.
    m->skin_vertadr[i] = vert;
    m->skin_vertnum[i] = static_cast<int>(s.vertex.size() / 3);
    m->skin_texcoordadr[i] = s.texcoord.empty() ? -1 : texcoord;
    m->skin_faceadr[i] = face;
    m->skin_facenum[i] = static_cast<int>(s.face.size() / 3);
    std::copy(s.vertex.begin(), s.vertex.end(), m->skin_vert.begin() + 3 * vert);
    std::copy(s.texcoord.begin(), s.texcoord.end(), m->skin_texcoord.begin() + 2 * texcoord);
    std::copy(s.face.begin(), s.face.end(), m->skin_face.begin() + 3 * face);
    vert += m->skin_vertnum[i];
    texcoord += static_cast<int>(s.texcoord.size() / 2);
    face += m->skin_facenum[i];

    // The bones and the vertices each carries.
    m->skin_boneadr[i] = bone;
    m->skin_bonenum[i] = static_cast<int>(s.bones.size());
    for (size_t j = 0; j < s.bones.size(); j++, bone++) {
      const mjcf::SkinBoneSpec& b = s.bones[j];
      std::copy(b.bindpos.begin(), b.bindpos.end(), &m->skin_bonebindpos[3 * bone]);
      std::copy(b.bindquat.begin(), b.bindquat.end(), &m->skin_bonebindquat[4 * bone]);
      m->skin_bonebodyid[bone] = skin.bodyid[j];
      m->skin_bonevertadr[bone] = bonevert;
      m->skin_bonevertnum[bone] = static_cast<int>(b.vertid.size());
      std::copy(b.vertid.begin(), b.vertid.end(), m->skin_bonevertid.begin() + bonevert);
      std::copy(b.vertweight.begin(), b.vertweight.end(),
                m->skin_bonevertweight.begin() + bonevert);
      bonevert += m->skin_bonevertnum[bone];
    }
  }
}

}  // namespace simlab::compiler
