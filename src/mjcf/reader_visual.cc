// <texture>, <material> and <light>: what a renderer needs to draw the model as MuJoCo's
// viewers do. Values start at MuJoCo's defaults (spec.h), then the class, then the element.
#include <string>

#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

const std::initializer_list<Keyword> kTextureTypes = {
    {"2d", kTexture2D}, {"cube", kTextureCube}, {"skybox", kTextureSkybox}};
const std::initializer_list<Keyword> kBuiltins = {
    {"none", kBuiltinNone}, {"gradient", kBuiltinGradient}, {"checker", kBuiltinChecker},
    {"flat", kBuiltinFlat}};
const std::initializer_list<Keyword> kMarks = {
    {"none", kMarkNone}, {"edge", kMarkEdge}, {"cross", kMarkCross}, {"random", kMarkRandom}};
const std::initializer_list<Keyword> kColorSpaces = {{"auto", 0}, {"linear", 1}, {"sRGB", 2}};
// mjtTextureRole, in order.
const std::initializer_list<Keyword> kTextureRoles = {
    {"user", 0}, {"rgb", 1},    {"occlusion", 2}, {"roughness", 3}, {"metallic", 4},
    {"normal", 5}, {"opacity", 6}, {"emissive", 7},  {"rgba", 8},      {"orm", 9}};
const std::initializer_list<Keyword> kLightTypes = {
    {"spot", 0}, {"directional", 1}, {"point", 2}, {"image", 3}};

// The six files of a cube texture given face by face, in MuJoCo's face order.
constexpr const char* kCubeFileAttrs[6] = {"fileright", "fileleft", "fileup",
                                           "filedown",  "filefront", "fileback"};

}  // namespace

void Reader::ReadTexture(const XmlElement& e, TextureSpec* tex) const {
  e.CheckAttributes({"name", "type", "colorspace", "content_type", "file", "gridsize",
                     "gridlayout", "fileright", "fileleft", "fileup", "filedown",
                     "filefront", "fileback", "builtin", "rgb1", "rgb2", "mark", "markrgb",
                     "random", "width", "height", "hflip", "vflip", "nchannel"});
  tex->src = e.src();
  e.Enum("type", &tex->type, kTextureTypes);
  e.Enum("colorspace", &tex->colorspace, kColorSpaces);
  e.Enum("builtin", &tex->builtin, kBuiltins);
  e.Enum("mark", &tex->mark, kMarks);
  e.Numbers("rgb1", tex->rgb1);
  e.Numbers("rgb2", tex->rgb2);
  e.Numbers("markrgb", tex->markrgb);
  e.Number("random", &tex->random);
  e.Int("width", &tex->width);
  e.Int("height", &tex->height);
  e.Int("nchannel", &tex->nchannel);
  e.Bool("hflip", &tex->hflip);
  e.Bool("vflip", &tex->vflip);
  e.Ints("gridsize", tex->gridsize.data(), 2);
  e.Text("gridlayout", &tex->gridlayout);
  if (tex->nchannel != 1 && tex->nchannel != 3 && tex->nchannel != 4) {
    e.Fail("nchannel must be 1, 3 or 4");
  }
  if (e.Text("file", &tex->file)) tex->path = AssetPath(tex->file, spec_->compiler.texturedir, e);
  for (int k = 0; k < 6; k++) {
    std::string face;
    if (e.Text(kCubeFileAttrs[k], &face)) {
      tex->cubefiles[k] = AssetPath(face, spec_->compiler.texturedir, e);
    }
  }
  // An unnamed texture is named by its file, as MuJoCo does.
  if (tex->src.name.empty() && !tex->file.empty()) tex->src.name = StemOf(tex->file);
}

void Reader::ReadMaterial(const XmlElement& e, MaterialSpec* mat, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"texture", "texrepeat", "texuniform", "emission", "specular",
                       "shininess", "reflectance", "metallic", "roughness", "rgba"});
  } else {
    e.CheckAttributes({"name", "class", "texture", "texrepeat", "texuniform", "emission",
                       "specular", "shininess", "reflectance", "metallic", "roughness",
                       "rgba"});
    mat->src = e.src();
  }
  e.Bool("texuniform", &mat->texuniform);
  e.Numbers("texrepeat", mat->texrepeat);
  e.Number("emission", &mat->emission);
  e.Number("specular", &mat->specular);
  e.Number("shininess", &mat->shininess);
  e.Number("reflectance", &mat->reflectance);
  e.Number("metallic", &mat->metallic);
  e.Number("roughness", &mat->roughness);
  e.Numbers("rgba", mat->rgba);

  // The texture attribute is the rgb role; <layer> children give roles one by one.
  bool attribute = e.Text("texture", &mat->textures[1]);
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement layer = Element(n);
    if (layer.tag() != "layer") Unknown(layer);
    if (attribute) layer.Fail("a material with a texture attribute cannot have layers");
    layer.CheckAttributes({"texture", "role"});
    int role = 0;
    if (!layer.Enum("role", &role, kTextureRoles)) layer.Fail("a layer needs a 'role'");
    layer.RequiredText("texture", &mat->textures[role]);
  }
}

void Reader::ReadLight(const XmlElement& e, LightSpec* light, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"pos", "dir", "bulbradius", "intensity", "range", "directional",
                       "type", "castshadow", "active", "attenuation", "cutoff", "exponent",
                       "ambient", "diffuse", "specular", "mode"});
  } else {
    e.CheckAttributes({"name", "class", "directional", "type", "castshadow", "active", "pos",
                       "dir", "bulbradius", "intensity", "range", "attenuation", "cutoff",
                       "exponent", "ambient", "diffuse", "specular", "mode", "target",
                       "texture"});
    light->src = e.src();
    e.Text("target", &light->target);
    e.Text("texture", &light->texture);
  }
  e.Enum("mode", &light->mode, kCamLightModes);
  // directional is the older spelling of type="directional" (spot when false).
  bool directional = false;
  if (e.Bool("directional", &directional)) light->type = directional ? 1 : 0;
  e.Enum("type", &light->type, kLightTypes);
  e.Bool("castshadow", &light->castshadow);
  e.Bool("active", &light->active);
  e.Number("bulbradius", &light->bulbradius);
  e.Number("intensity", &light->intensity);
  e.Number("range", &light->range);
  e.Numbers("pos", light->pos);
  e.Numbers("dir", light->dir);
  e.Numbers("attenuation", light->attenuation);
  e.Number("cutoff", &light->cutoff);
  e.Number("exponent", &light->exponent);
  e.Numbers("ambient", light->ambient);
  e.Numbers("diffuse", light->diffuse);
  e.Numbers("specular", light->specular);
}

}  // namespace simlab::mjcf
