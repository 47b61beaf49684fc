// Texture files (MuJoCo's mjCTexture::Load2D, LoadCubeSingle, LoadCubeSeparate): PNG
// images decoded by libpng to nchannel bytes per pixel as MuJoCo's decoder gives them
// (16-bit samples cut to their high byte, palettes and grey expanded, alpha dropped or
// added opaque), flipped when asked, and cut into cube faces by gridsize/gridlayout.
#ifndef SIMLAB_COMPILER_TEXTURE_PNG_H_
#define SIMLAB_COMPILER_TEXTURE_PNG_H_

#include <cstdint>

#include "compiler/compiler.h"
#include "mjcf/limits.h"
#include "mjcf/spec.h"

namespace simlab::compiler {

// Bytes one texture, and all of a model's, may hold (tex_data holds an int per byte).
inline constexpr uint64_t kMaxTextureBytes = mjcf::kMaxArrayBytes / 4;

// Fills t (size, bytes, and the colour space when s leaves it to the file) from the
// texture's file or files.
void LoadTextureFiles(const mjcf::ModelSpec& spec, const mjcf::TextureSpec& s, TextureImage* t);

// A height field's file (MuJoCo's mjCHField::LoadPNG and LoadCustom): a PNG read as
// grey, rows reversed (the image's top row is the field's +y edge), or MuJoCo's binary
// format (int32 nrow, int32 ncol, then nrow x ncol float32, native byte order); the
// content type from content_type, else from the extension (.png), else binary.
void LoadHFieldFile(const mjcf::ModelSpec& spec, const mjcf::HFieldSpec& s, int* nrow, int* ncol,
                    std::vector<float>* data);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_TEXTURE_PNG_H_
