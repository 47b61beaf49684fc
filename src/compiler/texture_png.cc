// Texture and height-field files: PNG decoding through libpng, flips, cube faces, and
// MuJoCo's binary height fields (see texture_png.h).
#include "compiler/texture_png.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "mjcf/assets.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

constexpr int kColorSpaceLinear = 1, kColorSpaceSRGB = 2;  // mjtColorSpace

// ---------------------------------------------------------------- decoding
// libpng reports errors by longjmp: everything the decoder writes lives in a PngJob,
// outside the frame that calls setjmp, and that frame holds no C++ objects.

struct PngJob {
  const std::string* bytes = nullptr;
  size_t at = 0;
  int nchannel = 3;
  uint32_t width = 0, height = 0;
  bool srgb = false;
  std::vector<uint8_t> pixels;
  std::vector<png_bytep> rows;
  char message[160] = "";
};

void ReadPngBytes(png_structp png, png_bytep out, size_t n) {
  auto* job = static_cast<PngJob*>(png_get_io_ptr(png));
  if (n > job->bytes->size() - job->at) png_error(png, "the file ends too early");
  std::memcpy(out, job->bytes->data() + job->at, n);
  job->at += n;
}

void PngError(png_structp png, png_const_charp message) {
  auto* job = static_cast<PngJob*>(png_get_error_ptr(png));
  std::snprintf(job->message, sizeof(job->message), "%s", message);
  png_longjmp(png, 1);
}

void PngWarning(png_structp, png_const_charp) {}

// Samples as MuJoCo's decoder converts them: 8 bits (16-bit samples keep their high
// byte, 1/2/4-bit grey is scaled up), palettes expanded, grey made RGB, and alpha
// dropped for 3 channels or added opaque for 4.
void SetTransforms(png_structp png, png_infop info, int nchannel) {
  int type = png_get_color_type(png, info);
  png_set_strip_16(png);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) {
    png_set_expand_gray_1_2_4_to_8(png);
  }
  bool trns = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  // (expanding a palette turns its transparency into alpha)
  bool alpha = (type & PNG_COLOR_MASK_ALPHA) != 0 || (type == PNG_COLOR_TYPE_PALETTE && trns);
  if (nchannel == 4 && trns && !alpha) {
    png_set_tRNS_to_alpha(png);
    alpha = true;
  }
  bool grey = (type & PNG_COLOR_MASK_COLOR) == 0;
  if (nchannel >= 3 && grey) png_set_gray_to_rgb(png);
  if (nchannel == 1 && !grey) png_error(png, "a colour image cannot load as 1 channel");
  if (nchannel != 4 && alpha) png_set_strip_alpha(png);
  if (nchannel == 4 && !alpha) png_set_filler(png, 0xff, PNG_FILLER_AFTER);
}

// Decodes job->bytes into job->pixels; false with job->message on failure.
bool DecodePng(PngJob* job) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, job, PngError, PngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, job, ReadPngBytes);
  png_read_info(png, info);
  SetTransforms(png, info, job->nchannel);
  png_read_update_info(png, info);
  job->width = png_get_image_width(png, info);
  job->height = png_get_image_height(png, info);
  job->srgb = png_get_valid(png, info, PNG_INFO_sRGB) != 0;
  size_t row = png_get_rowbytes(png, info);
  if (row != static_cast<size_t>(job->width) * job->nchannel) png_error(png, "unexpected row size");
  if (static_cast<uint64_t>(row) * job->height > kMaxTextureBytes) png_error(png, "image too large");
  job->pixels.resize(row * job->height);
  job->rows.resize(job->height);
  for (uint32_t r = 0; r < job->height; r++) job->rows[r] = job->pixels.data() + r * row;
  png_read_image(png, job->rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// ---------------------------------------------------------------- one image

struct Decoded {
  int width = 0, height = 0;
  bool srgb = false;
  std::vector<uint8_t> pixels;
};

// The content type a file is read as: content_type if given, else from its extension.
bool IsPng(const std::string& path) {
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == "png";
}

// Mirrors the image left-right and/or top-bottom, as asked.
void Flip(const mjcf::TextureSpec& s, int nchannel, Decoded* img) {
  int w = img->width, h = img->height;
  auto swap_pixels = [&](size_t a, size_t b) {
    for (int k = 0; k < nchannel; k++) std::swap(img->pixels[a + k], img->pixels[b + k]);
  };
  if (s.hflip) {
    for (int r = 0; r < h; r++) {
      for (int c = 0; c < w / 2; c++) {
        swap_pixels(nchannel * (static_cast<size_t>(r) * w + c),
                    nchannel * (static_cast<size_t>(r) * w + (w - 1 - c)));
      }
    }
  }
  if (s.vflip) {
    for (int r = 0; r < h / 2; r++) {
      for (int c = 0; c < w; c++) {
        swap_pixels(nchannel * (static_cast<size_t>(r) * w + c),
                    nchannel * (static_cast<size_t>(h - 1 - r) * w + c));
      }
    }
  }
}

Decoded LoadImage(const mjcf::ModelSpec& spec, const mjcf::TextureSpec& s, const std::string& path) {
  if (!IsPng(path)) {
    ThrowAt(s.src, "unsupported texture file '" + path + "': simlab reads PNG images");
  }
  std::string bytes;
  if (!mjcf::ReadFileOrAsset(path, spec.assets.get(), &bytes)) {
    ThrowAt(s.src, "cannot open texture file '" + path + "'" + mjcf::NotAmongAssets(spec.assets.get()));
  }
  PngJob job;
  job.bytes = &bytes;
  job.nchannel = s.nchannel;
  if (!DecodePng(&job)) {
    ThrowAt(s.src, "cannot read PNG file '" + path + "': " + job.message);
  }
  Decoded img;
  img.width = static_cast<int>(job.width);
  img.height = static_cast<int>(job.height);
  img.srgb = job.srgb;
  img.pixels = std::move(job.pixels);
  Flip(s, s.nchannel, &img);
  return img;
}

// The colour space a file gives when the texture leaves it to the file.
int ColorSpace(const mjcf::TextureSpec& s, bool srgb) {
  if (s.colorspace != 0) return s.colorspace;
  return srgb ? kColorSpaceSRGB : kColorSpaceLinear;
}

// Fills every face not in `loaded` with rgb1 (3 bytes per pixel, as MuJoCo).
void FillMissingFaces(const mjcf::TextureSpec& s, const bool loaded[6], TextureImage* t) {
  size_t face = static_cast<size_t>(t->width) * t->width;
  for (int f = 0; f < 6; f++) {
    if (loaded[f]) continue;
    for (size_t p = 0; p < face; p++) {
      for (int k = 0; k < 3; k++) {
        t->data[3 * (f * face + p) + k] = ColourByte(s.rgb1[k]);
      }
    }
  }
}

// The index of a gridlayout symbol's face, -1 for '.'.
int GridFace(const mjcf::TextureSpec& s, char symbol) {
  const std::string faces = "RLUDFB";
  if (symbol == '.') return -1;
  size_t at = faces.find(symbol);
  if (at == std::string::npos) ThrowAt(s.src, "gridlayout symbol is not among '.RLUDFB'");
  return static_cast<int>(at);
}

// A cube or skybox from one image: the same face six times (gridsize 1 1), or faces
// cut from a grid of squares.
void LoadCubeSingle(const mjcf::ModelSpec& spec, const mjcf::TextureSpec& s, TextureImage* t) {
  int rows = s.gridsize[0], cols = s.gridsize[1];
  if (rows < 1 || cols < 1 || rows * cols > 12) {
    ThrowAt(s.src, "gridsize must be non-zero and no more than 12 squares");
  }
  Decoded img = LoadImage(spec, s, s.path);
  t->colorspace = ColorSpace(s, img.srgb);
  if (img.width / cols != img.height / rows || img.width % cols || img.height % rows) {
    ThrowAt(s.src, "PNG size must be integer multiple of gridsize in texture '" + s.file + "'");
  }
  bool repeated = rows == 1 && cols == 1;
  t->width = repeated ? img.width : img.width / cols;
  t->height = repeated ? img.width : 6 * t->width;
  size_t face = static_cast<size_t>(t->width) * t->width;
  t->data.assign(3 * face * (repeated ? 1 : 6), 0);
  if (repeated) {
    std::copy_n(img.pixels.begin(), 3 * face, t->data.begin());
    return;
  }
  bool loaded[6] = {false, false, false, false, false, false};
  for (int k = 0; k < rows * cols && k < static_cast<int>(s.gridlayout.size()); k++) {
    int f = GridFace(s, s.gridlayout[k]);
    if (f < 0) continue;
    int r0 = t->width * (k / cols), c0 = t->width * (k % cols);
    for (int j = 0; j < t->width; j++) {
      const uint8_t* from = img.pixels.data() + 3 * ((static_cast<size_t>(r0) + j) * img.width + c0);
      std::copy_n(from, 3 * t->width, t->data.data() + 3 * (f * face + static_cast<size_t>(j) * t->width));
    }
    loaded[f] = true;
  }
  FillMissingFaces(s, loaded, t);
}

// A cube or skybox from up to six square images, one per face.
void LoadCubeSeparate(const mjcf::ModelSpec& spec, const mjcf::TextureSpec& s, TextureImage* t) {
  bool loaded[6] = {false, false, false, false, false, false};
  for (int f = 0; f < 6; f++) {
    if (s.cubefiles[f].empty()) continue;
    Decoded img = LoadImage(spec, s, s.cubefiles[f]);
    t->colorspace = ColorSpace(s, img.srgb);
    if (img.width != img.height) ThrowAt(s.src, "non-square PNG file '" + s.cubefiles[f] + "'");
    if (t->width == 0) {
      t->width = img.width;
      t->height = 6 * img.width;
      t->data.assign(3 * static_cast<size_t>(t->width) * t->height, 0);
    } else if (t->width != img.width) {
      ThrowAt(s.src, "PNG files of a cube texture must have the same size");
    }
    size_t face = static_cast<size_t>(t->width) * t->width;
    std::copy_n(img.pixels.begin(), 3 * face, t->data.begin() + 3 * f * face);
    loaded[f] = true;
  }
  FillMissingFaces(s, loaded, t);
}

}  // namespace

namespace {

// The grid size a height-field file gives, checked against the model's budget (its
// hfield_data holds a double per sample) before anything that size is made.
void CheckHFieldGrid(const mjcf::HFieldSpec& s, int64_t nrow, int64_t ncol) {
  if (nrow < 1 || ncol < 1) {
    ThrowAt(s.src, "non-positive hfield dimensions in file '" + s.path + "'");
  }
  if (static_cast<uint64_t>(nrow) * static_cast<uint64_t>(ncol) * sizeof(double) > mjcf::kMaxArrayBytes) {
    ThrowAt(s.src, "hfield file '" + s.path + "' is " + std::to_string(nrow) + " x " +
                       std::to_string(ncol) + ", over simlab's limit for height field data");
  }
}

// A PNG as grey samples: decoded to RGB and the red sample kept, which is lodepng's grey
// of any pixel (a grey image's own samples; the high byte of 16-bit ones).
void LoadHFieldPng(const mjcf::HFieldSpec& s, const std::string& bytes, int* nrow, int* ncol,
                   std::vector<float>* data) {
  PngJob job;
  job.bytes = &bytes;
  job.nchannel = 3;
  if (!DecodePng(&job)) ThrowAt(s.src, "cannot read PNG file '" + s.path + "': " + job.message);
  CheckHFieldGrid(s, job.height, job.width);
  *nrow = static_cast<int>(job.height);
  *ncol = static_cast<int>(job.width);
  data->resize(static_cast<size_t>(*nrow) * *ncol);
  for (int r = 0; r < *nrow; r++) {
    const uint8_t* row = job.pixels.data() + static_cast<size_t>(*nrow - 1 - r) * *ncol * 3;
    for (int c = 0; c < *ncol; c++) (*data)[static_cast<size_t>(r) * *ncol + c] = row[3 * c];
  }
}

// MuJoCo's binary height field: two int32 sizes, then the samples; the file's size must
// be exactly that.
void LoadHFieldBinary(const mjcf::HFieldSpec& s, const std::string& bytes, int* nrow, int* ncol,
                      std::vector<float>* data) {
  if (bytes.size() < 2 * sizeof(int32_t)) ThrowAt(s.src, "hfield missing header '" + s.path + "'");
  int32_t size[2];
  std::memcpy(size, bytes.data(), sizeof(size));
  CheckHFieldGrid(s, size[0], size[1]);
  const size_t n = static_cast<size_t>(size[0]) * static_cast<size_t>(size[1]);
  if (bytes.size() != n * sizeof(float) + sizeof(size)) {
    ThrowAt(s.src, "unexpected file size in file '" + s.path + "'");
  }
  *nrow = size[0];
  *ncol = size[1];
  data->resize(n);
  std::memcpy(data->data(), bytes.data() + sizeof(size), n * sizeof(float));
}

}  // namespace

void LoadHFieldFile(const mjcf::ModelSpec& spec, const mjcf::HFieldSpec& s, int* nrow, int* ncol,
                    std::vector<float>* data) {
  const bool png = s.content_type.empty() ? IsPng(s.path) : s.content_type == "image/png";
  if (!s.content_type.empty() && !png && s.content_type != "image/vnd.mujoco.hfield") {
    ThrowAt(s.src, "unsupported content type: '" + s.content_type + "'");
  }
  std::string bytes;
  if (!mjcf::ReadFileOrAsset(s.path, spec.assets.get(), &bytes)) {
    ThrowAt(s.src, "could not read hfield file '" + s.path + "'" + mjcf::NotAmongAssets(spec.assets.get()));
  }
  if (png) {
    LoadHFieldPng(s, bytes, nrow, ncol, data);
  } else {
    LoadHFieldBinary(s, bytes, nrow, ncol, data);
  }
}

void LoadTextureFiles(const mjcf::ModelSpec& spec, const mjcf::TextureSpec& s, TextureImage* t) {
  bool faces = false;
  for (const std::string& f : s.cubefiles) faces = faces || !f.empty();
  if (!s.file.empty()) {
    if (s.type == mjcf::kTexture2D) {
      Decoded img = LoadImage(spec, s, s.path);
      t->width = img.width;
      t->height = img.height;
      t->colorspace = ColorSpace(s, img.srgb);
      t->data = std::move(img.pixels);
    } else {
      LoadCubeSingle(spec, s, t);
    }
  } else if (s.type == mjcf::kTexture2D) {
    ThrowAt(s.src, "a 2D texture needs a file or a builtin pattern");
  } else if (faces) {
    LoadCubeSeparate(spec, s, t);
  } else {
    ThrowAt(s.src, "a cube or skybox texture needs a file, six face files or a builtin pattern");
  }
}

}  // namespace simlab::compiler
