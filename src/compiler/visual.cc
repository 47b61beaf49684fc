// Textures, materials and lights (MuJoCo's mjCTexture, mjCMaterial, mjCLight): what a
// renderer needs to draw a model as MuJoCo's viewers do. Nothing here acts on the physics.
//
// Textures become bytes (tex_data), nchannel per pixel, row by row: a builtin pattern
// (gradient, checker, flat, with edge/cross/random marks) made as MuJoCo makes it, or a
// PNG file (texture_png.cc). Cube and skybox textures are six square faces stacked
// (right, left, up, down, front, back), so their height is six widths.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "compiler/texture_png.h"
#include "engine/engine.h"
#include "math/elementary.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

using Pixel = std::array<uint8_t, 3>;

// A colour in [0, 1] as bytes, truncated as MuJoCo converts it.
Pixel ToBytes(const std::array<double, 3>& rgb) {
  Pixel p;
  for (int k = 0; k < 3; k++) p[k] = ColourByte(rgb[k]);
  return p;
}

// An image being made: width x height pixels of nchannel bytes.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t>* data = nullptr;

  // (MuJoCo's builtin patterns step 3 bytes per pixel whatever nchannel is)
  uint8_t* At(int face, int r, int c) const {
    size_t pixel = (static_cast<size_t>(face) * width + r) * width + c;
    return data->data() + 3 * pixel;
  }
  void Set(int face, int r, int c, const Pixel& p) const {
    uint8_t* at = At(face, r, c);
    for (int k = 0; k < 3; k++) at[k] = p[k];
  }
};

// The blend of rgb1 and rgb2 at pos in (-1, 1) through MuJoCo's sigmoid.
Pixel Blend(const std::array<double, 3>& rgb1, const std::array<double, 3>& rgb2, double pos) {
  double alpha = 0.5 * (1 + pos / std::sqrt(1 + pos * pos) / (1 / std::sqrt(2.0)));
  alpha = std::min(1.0, std::max(0.0, alpha));
  Pixel p;
  for (int k = 0; k < 3; k++) {
    p[k] = ColourByte(alpha * rgb1[k] + (1 - alpha) * rgb2[k]);
  }
  return p;
}

// A 2 x 2 checker on one face (rows and columns of width x height): a on the diagonal.
void Checker(const Image& img, int face, int rows, const Pixel& a, const Pixel& b) {
  for (int r = 0; r < rows; r++) {
    for (int c = 0; c < img.width; c++) {
      bool diagonal = (r < rows / 2) == (c < img.width / 2);
      img.Set(face, r, c, diagonal ? a : b);
    }
  }
}

// Random dots of markrgb with the given probability, from MuJoCo's fixed seed (a 64-bit
// Mersenne twister seeded with 42, one draw per pixel, u = draw / 2^64).
void RandomDots(const Image& img, int rows, const Pixel& mark, double probability) {
  std::mt19937_64 rng(42);
  for (int r = 0; r < rows; r++) {
    for (int c = 0; c < img.width; c++) {
      double u = static_cast<double>(rng()) / 18446744073709551616.0;
      if (u < probability) {
        uint8_t* at = img.data->data() + 3 * (static_cast<size_t>(r) * img.width + c);
        for (int k = 0; k < 3; k++) at[k] = mark[k];
      }
    }
  }
}

// Edge or cross marks on `faces` faces of rows x width.
void Marks(const mjcf::TextureSpec& s, const Image& img, int faces, int rows) {
  Pixel mark = ToBytes(s.markrgb);
  for (int f = 0; f < faces; f++) {
    if (s.mark == mjcf::kMarkEdge) {
      for (int r = 0; r < rows; r++) {
        img.Set(f, r, 0, mark);
        img.Set(f, r, img.width - 1, mark);
      }
      for (int c = 0; c < img.width; c++) {
        img.Set(f, 0, c, mark);
        img.Set(f, rows - 1, c, mark);
      }
    } else if (s.mark == mjcf::kMarkCross) {
      for (int r = 0; r < rows; r++) img.Set(f, r, img.width / 2, mark);
      for (int c = 0; c < img.width; c++) img.Set(f, rows / 2, c, mark);
    }
  }
}

// A builtin pattern on a 2D texture (MuJoCo Builtin2D).
void Builtin2D(const mjcf::TextureSpec& s, const Image& img) {
  Pixel rgb1 = ToBytes(s.rgb1), rgb2 = ToBytes(s.rgb2);
  int w = img.width, h = img.height;
  for (int r = 0; r < h; r++) {
    for (int c = 0; c < w; c++) {
      if (s.builtin == mjcf::kBuiltinGradient) {
        double x = 2 * c / static_cast<double>(w - 1) - 1;
        double y = 1 - 2 * r / static_cast<double>(h - 1);
        img.Set(0, r, c, Blend(s.rgb2, s.rgb1, 2 * std::sqrt(x * x + y * y) - 1));
      } else if (s.builtin == mjcf::kBuiltinFlat) {
        img.Set(0, r, c, rgb1);
      }
    }
  }
  if (s.builtin == mjcf::kBuiltinChecker) Checker(img, 0, h, rgb1, rgb2);
  Marks(s, img, 1, h);
  if (s.mark == mjcf::kMarkRandom && s.random > 0) RandomDots(img, h, ToBytes(s.markrgb), s.random);
}

// A builtin pattern on the six faces of a cube or skybox (MuJoCo BuiltinCube).
void BuiltinCube(const mjcf::TextureSpec& s, const Image& img) {
  Pixel rgb1 = ToBytes(s.rgb1), rgb2 = ToBytes(s.rgb2);
  int w = img.width;
  for (int r = 0; r < w; r++) {
    for (int c = 0; c < w; c++) {
      if (s.builtin == mjcf::kBuiltinGradient) {
        // Elevation of the pixel's direction: on the sides, and from the up/down faces.
        double x = 2 * c / static_cast<double>(w - 1) - 1;
        double y = 1 - 2 * r / static_cast<double>(w - 1);
        double norm = std::sqrt(1 + x * x + y * y);
        double side = math::Asin(y / norm) / (0.5 * M_PI);
        double up = 1 - math::Acos(1.0 / norm) / (0.5 * M_PI);
        Pixel p = Blend(s.rgb1, s.rgb2, side);
        for (int f : {0, 1, 4, 5}) img.Set(f, r, c, p);
        img.Set(2, r, c, Blend(s.rgb1, s.rgb2, up));
        img.Set(3, r, c, Blend(s.rgb1, s.rgb2, -up));
      } else if (s.builtin == mjcf::kBuiltinFlat) {
        for (int f : {0, 1, 2, 4, 5}) img.Set(f, r, c, rgb1);
        img.Set(3, r, c, rgb2);
      }
    }
  }
  if (s.builtin == mjcf::kBuiltinChecker) {
    for (int f = 0; f < 6; f++) Checker(img, f, w, f < 4 ? rgb1 : rgb2, f < 4 ? rgb2 : rgb1);
  }
  Marks(s, img, 6, w);
  if (s.mark == mjcf::kMarkRandom && s.random > 0) {
    RandomDots(img, img.height, ToBytes(s.markrgb), s.random);
  }
}

// The size of a builtin texture, checked; cube textures are six square faces.
void BuiltinSize(const mjcf::TextureSpec& s, TextureImage* t) {
  if (s.width < 1) ThrowAt(s.src, "invalid width of builtin texture");
  t->width = s.width;
  if (s.type == mjcf::kTexture2D) {
    if (s.height < 1) ThrowAt(s.src, "invalid height of builtin texture");
    t->height = s.height;
  } else {
    if (s.width >= std::numeric_limits<int>::max() / 6) {
      ThrowAt(s.src, "invalid width of builtin texture");
    }
    t->height = 6 * s.width;
  }
  uint64_t bytes = static_cast<uint64_t>(t->width) * t->height * s.nchannel;
  if (bytes > kMaxTextureBytes) ThrowAt(s.src, "builtin texture too large");
}

TextureImage CompileTexture(const mjcf::ModelSpec& spec, const mjcf::TextureSpec& s) {
  TextureImage t;
  t.nchannel = s.nchannel;
  t.colorspace = s.colorspace;
  if (s.builtin != mjcf::kBuiltinNone) {
    if (s.nchannel == 1) ThrowAt(s.src, "a builtin texture needs 3 or 4 channels");
    BuiltinSize(s, &t);
    t.data.assign(static_cast<size_t>(t.width) * t.height * t.nchannel, 0);
    Image img{t.width, t.height, &t.data};
    if (s.type == mjcf::kTexture2D) {
      Builtin2D(s, img);
    } else {
      BuiltinCube(s, img);
    }
    return t;
  }
  LoadTextureFiles(spec, s, &t);
  return t;
}

// The id of a named asset, or -1 when the name is empty.
int AssetId(const mjcf::Source& src, const NameIndex& names, const std::string& name,
            const std::string& kind) {
  return name.empty() ? -1 : FindNamed(src, names, name, kind);
}

void LayoutTextures(const mjcf::ModelSpec& spec, const std::vector<TextureImage>& images,
                    Model* m) {
  NameIndex seen;
  int adr = 0;
  for (int i = 0; i < m->ntex; i++) {
    const mjcf::TextureSpec& s = spec.textures[i];
    const TextureImage& t = images[i];
    if (!s.src.name.empty() && !seen.Insert(s.src.name, i)) {
      ThrowAt(s.src, "repeated texture name '" + s.src.name + "'");
    }
    m->tex_names[i] = s.src.name;
    m->tex_type[i] = s.type;
    m->tex_colorspace[i] = t.colorspace;
    m->tex_width[i] = t.width;
    m->tex_height[i] = t.height;
    m->tex_nchannel[i] = t.nchannel;
    m->tex_adr[i] = adr;
    for (size_t k = 0; k < t.data.size(); k++) m->tex_data[adr + k] = t.data[k];
    adr += static_cast<int>(t.data.size());
  }
}

void LayoutMaterials(const mjcf::ModelSpec& spec, Model* m) {
  NameIndex textures(m->tex_names), seen;
  for (int i = 0; i < m->nmat; i++) {
    const mjcf::MaterialSpec& s = spec.materials[i];
    if (!s.src.name.empty() && !seen.Insert(s.src.name, i)) {
      ThrowAt(s.src, "repeated material name '" + s.src.name + "'");
    }
    m->mat_names[i] = s.src.name;
    for (int r = 0; r < kNTexRole; r++) {
      m->mat_texid[kNTexRole * i + r] = AssetId(s.src, textures, s.textures[r], "texture");
    }
    m->mat_texuniform[i] = s.texuniform;
    // (single precision, as MuJoCo keeps them)
    for (int k = 0; k < 2; k++) m->mat_texrepeat[2 * i + k] = static_cast<float>(s.texrepeat[k]);
    m->mat_emission[i] = static_cast<float>(s.emission);
    m->mat_specular[i] = static_cast<float>(s.specular);
    m->mat_shininess[i] = static_cast<float>(s.shininess);
    m->mat_reflectance[i] = static_cast<float>(s.reflectance);
    m->mat_metallic[i] = static_cast<float>(s.metallic);
    m->mat_roughness[i] = static_cast<float>(s.roughness);
    for (int k = 0; k < 4; k++) m->mat_rgba[4 * i + k] = static_cast<float>(s.rgba[k]);
  }
}

// The material each geom and site names, or -1.
void LayoutMaterialUses(const CompileState& state, Model* m) {
  NameIndex materials(m->mat_names);
  for (int g = 0; g < m->ngeom; g++) {
    const mjcf::GeomSpec& s = *state.geoms[g].spec;
    m->geom_matid[g] = AssetId(s.src, materials, s.material, "material");
  }
  for (int i = 0; i < m->nsite; i++) {
    const mjcf::SiteSpec& s = *state.sites[i].spec;
    m->site_matid[i] = AssetId(s.src, materials, s.material, "material");
  }
}

// A light's spec with the id of the body it sits in.
struct LightRef {
  const mjcf::LightSpec* spec = nullptr;
  int body = 0;
};

// Lights in body order (bodies are depth-first), each body's in XML order, then those of
// the bodies fused into it (with the pose they had there, as MuJoCo keeps it).
std::vector<LightRef> CollectLights(const CompileState& state) {
  std::vector<LightRef> lights;
  for (const BodyState& b : state.bodies) {
    for (const mjcf::LightSpec& l : b.spec->lights) lights.push_back({&l, b.id});
    for (const mjcf::BodySpec* f : b.fused) {
      for (const mjcf::LightSpec& l : f->lights) lights.push_back({&l, b.id});
    }
  }
  return lights;
}

// Position and unit direction in the body frame, through any enclosing frames.
void LightPose(const mjcf::CompilerSpec& model, const mjcf::LightSpec& s, double* pos, double* dir) {
  math::Copy3(pos, s.pos.data());
  math::Copy3(dir, s.dir.data());
  if (s.frame) {
    double fpos[3], fquat[4], unit[4] = {1, 0, 0, 0};
    FramePose(*s.frame, model, fpos, fquat);
    AccumulateChild(fpos, fquat, pos, unit);
    double turned[3];
    math::RotVecQuat(turned, dir, fquat);
    math::Copy3(dir, turned);
  }
  double norm = math::Norm3(dir);
  if (norm < 1e-14) ThrowAt(s.src, "zero direction in light");
  for (int k = 0; k < 3; k++) dir[k] /= norm;
}

void LayoutLight(const mjcf::ModelSpec& spec, const LightRef& ref, const NameIndex& bodies,
                 const NameIndex& textures, int i, Model* m) {
  const mjcf::LightSpec& s = *ref.spec;
  m->light_names[i] = s.src.name;
  m->light_mode[i] = s.mode;
  m->light_bodyid[i] = ref.body;
  m->light_targetbodyid[i] = AssetId(s.src, bodies, s.target, "body");
  m->light_type[i] = s.type;
  m->light_texid[i] = AssetId(s.src, textures, s.texture, "texture");
  m->light_castshadow[i] = s.castshadow;
  m->light_active[i] = s.active;
  LightPose(spec.compiler, s, &m->light_pos[3 * i], &m->light_dir[3 * i]);
  // (single precision, as MuJoCo keeps them)
  m->light_bulbradius[i] = static_cast<float>(s.bulbradius);
  m->light_intensity[i] = static_cast<float>(s.intensity);
  m->light_range[i] = static_cast<float>(s.range);
  m->light_cutoff[i] = static_cast<float>(s.cutoff);
  m->light_exponent[i] = static_cast<float>(s.exponent);
  for (int k = 0; k < 3; k++) {
    m->light_attenuation[3 * i + k] = static_cast<float>(s.attenuation[k]);
    m->light_ambient[3 * i + k] = static_cast<float>(s.ambient[k]);
    m->light_diffuse[3 * i + k] = static_cast<float>(s.diffuse[k]);
    m->light_specular[3 * i + k] = static_cast<float>(s.specular[k]);
  }
}

}  // namespace

std::vector<TextureImage> CompileTextures(const mjcf::ModelSpec& spec) {
  std::vector<TextureImage> images;
  uint64_t total = 0;
  for (const mjcf::TextureSpec& s : spec.textures) {
    images.push_back(CompileTexture(spec, s));
    total += images.back().data.size();
    if (total > kMaxTextureBytes) ThrowAt(s.src, "the model's textures are too large");
  }
  return images;
}

void VisualSizes(const mjcf::ModelSpec& spec, const CompileState& state,
                 const std::vector<TextureImage>& images, Model* m) {
  m->nlight = static_cast<int>(CollectLights(state).size());
  m->ntex = static_cast<int>(images.size());
  m->ntexdata = 0;
  for (const TextureImage& t : images) m->ntexdata += static_cast<int>(t.data.size());
  m->nmat = static_cast<int>(spec.materials.size());
}

void LayoutVisual(const mjcf::ModelSpec& spec, const CompileState& state,
                  const std::vector<TextureImage>& images, Model* m) {
  LayoutTextures(spec, images, m);
  LayoutMaterials(spec, m);
  LayoutMaterialUses(state, m);
  std::vector<LightRef> lights = CollectLights(state);
  NameIndex bodies(m->body_names), textures(m->tex_names);
  for (size_t i = 0; i < lights.size(); i++) {
    LayoutLight(spec, lights[i], bodies, textures, static_cast<int>(i), m);
    // (an aligned body's lights: the position moved, the direction turned)
    const BodyState& b = state.bodies[lights[i].body];
    double unit[4] = {1, 0, 0, 0}, turned[3];
    AlignedPose(b, &m->light_pos[3 * i], unit);
    if (b.aligned) {
      math::RotVecQuat(turned, &m->light_dir[3 * i], b.align_quat);
      math::Copy3(&m->light_dir[3 * i], turned);
    }
  }
}

}  // namespace simlab::compiler
