#include "glint/render/env/environment.h"

#include "glint/core/error.h"
#include "glint/core/locations.h"
#include "glint/image/envmap.h"
#include "glint/image/srgb.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"

#include <cmath>
#include <vector>

namespace glint::render::env {
namespace fs = std::filesystem;

fs::path findEnvironment(std::string_view name) {
  return findDataFile(fs::path("env") / (std::string(name) + ".exr"), fmt::format("environment '{}'", name));
}

Image loadEquirect(const fs::path& path) {
  Image image = loadImage(path);  // Error(Input) for missing or corrupt files
  glint::validateEquirect(image, path.filename().string());
  return image;
}

namespace {
// 8- and 16-bit images hold sRGB-encoded colour: decode to linear so exposure and the
// tone curve treat every input alike.
Image linearFloat(const Image& image) {
  if (image.type() == PixelType::F32) return image;
  Image out = image.converted(PixelType::F32);
  for (float& v : out.pixels<float>()) v = srgbDecode(v);
  return out;
}

GLenum formatFor(int channels) { return channels == 4 ? GL_RGBA : GL_RGB; }
}  // namespace

gl::Texture cubeFromEquirect(const Image& equirect, const CubeFromEquirectOptions& options) {
  glint::validateEquirect(equirect, "equirect");
  if (options.faceSize <= 0) fail(ErrorKind::Usage, "cube face size must be positive, got {}", options.faceSize);
  const Image hdr = linearFloat(equirect);
  gl::Texture source(GL_TEXTURE_2D, "equirect");
  source.storage(GL_RGBA32F, hdr.width(), hdr.height());
  source.upload(0, hdr.width(), hdr.height(), formatFor(hdr.channels()), GL_FLOAT, hdr.bytes().data());
  source.filtering(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  source.parameter(GL_TEXTURE_WRAP_S, GLint(GL_REPEAT));  // longitude wraps around

  gl::Texture cube(GL_TEXTURE_CUBE_MAP, options.label);
  cube.storage(GL_RGBA8, options.faceSize, options.faceSize, 1, 0);
  cube.filtering(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);

  const SavedTarget saved;  // the caller's framebuffer and viewport, put back on return
  FullscreenPass pass("env/equirect_to_cube.frag");
  pass.program().set("uSize", options.faceSize);
  pass.program().set("uSamples", options.samples);
  pass.program().set("uExposure", options.exposure);
  auto fb = gl::Framebuffer::create("equirect-to-cube");
  source.bind(0);
  for (int face = 0; face < glint::kCubeFaces; ++face) {
    // The face is the colour attachment: the render writes straight into the cube map.
    fb.attachLayer(GL_COLOR_ATTACHMENT0, cube, face, 0);
    if (face == 0) fb.checkComplete();
    fb.bind();
    glViewport(0, 0, options.faceSize, options.faceSize);
    pass.program().set("uFace", face);
    pass.draw();
  }
  glBindTextureUnit(0, 0);
  cube.generateMipmap();
  return cube;
}

gl::Texture cubeFromFaces(std::span<const Image> faces, std::span<const std::string> names, float exposure) {
  glint::validateCubeFaces(faces, names);
  const int size = faces[0].width();
  gl::Texture cube(GL_TEXTURE_CUBE_MAP, "cube-faces");
  cube.storage(GL_RGBA8, size, size, 1, 0);
  cube.filtering(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  for (int face = 0; face < glint::kCubeFaces; ++face) {
    const Image& f = faces[std::size_t(face)];
    Image rgba(size, size, 4);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        vec3 c(f.at(x, y, 0), f.at(x, y, 1), f.at(x, y, 2));
        if (f.type() == PixelType::F32) c = glint::displayEncode(c, exposure);
        for (int k = 0; k < 3; ++k) rgba.set(x, y, k, c[k]);
        rgba.set(x, y, 3, 1.0f);
      }
    cube.upload(0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, rgba.bytes().data(), face);
  }
  cube.generateMipmap();
  return cube;
}

gl::Texture loadCubeFaces(std::span<const fs::path> paths, float exposure) {
  if (paths.size() != std::size_t(glint::kCubeFaces)) {
    fail(ErrorKind::Input, "a cube map needs 6 face images (+X -X +Y -Y +Z -Z), got {}", paths.size());
  }
  std::vector<Image> faces;
  std::vector<std::string> names;
  for (const auto& p : paths) {
    faces.push_back(loadImage(p));
    names.push_back(p.filename().string());
  }
  return cubeFromFaces(faces, names, exposure);
}

gl::Texture sphereMapFromCube(const gl::Texture& cube, const SphereMapOptions& options) {
  if (cube.target() != GL_TEXTURE_CUBE_MAP) fail(ErrorKind::Internal, "sphereMapFromCube needs a cube map");
  if (options.size <= 0) fail(ErrorKind::Usage, "sphere map size must be positive, got {}", options.size);
  gl::Texture map(GL_TEXTURE_2D, options.label);
  map.storage(GL_RGBA8, options.size, options.size, 1, 0);
  map.filtering(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
  const SavedTarget saved;
  FullscreenPass pass("env/sphere_map_from_cube.frag");
  pass.program().set("uFrameToWorld", glm::transpose(options.worldToFrame));
  pass.program().set("uSize", options.size);
  pass.program().set("uSamples", options.samples);
  auto fb = gl::Framebuffer::create("sphere-map-from-cube");
  fb.attach(GL_COLOR_ATTACHMENT0, map, 0);
  fb.checkComplete();
  fb.bind();
  glViewport(0, 0, options.size, options.size);
  PipelineState{.depthTest = false, .depthWrite = false, .seamlessCubeMap = true}.apply();
  cube.bind(0);
  pass.drawWithCurrentState();
  glBindTextureUnit(0, 0);
  map.generateMipmap();
  return map;
}

}  // namespace glint::render::env
