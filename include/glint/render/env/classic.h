#pragma once
// glint/render/env/classic.h — environment mapping with the 2001 fixed-function API, as
// the WWDC 2001 talk shows it: glTexGen(GL_REFLECTION_MAP) + glEnable(GL_TEXTURE_CUBE_MAP), and
// glTexGen(GL_SPHERE_MAP) + GL_TEXTURE_2D. Needs a compatibility-profile context
// (SceneDesc::profile = gl::Profile::Compatibility); constructing on a core context
// throws Error(NoGpu), and scenes using it are skipped where no such context exists.
//
// Contents
//   ClassicMesh          positions + normals in a vertex buffer, drawn with
//                        glVertexPointer / glNormalPointer client state
//   ClassicEnvironment   skybox, cube-mapped and sphere-mapped mirrors
//
// The texgen modes work in eye space. A cube map lives in world space, so the reflection
// vector is rotated back to world space through the texture matrix (the inverse view
// rotation) — the standard 2001 trick. GL_SPHERE_MAP has no such hook: (s, t) are made
// from the eye-space vector, so a sphere map is right only for the view it was made for.
//
// Every draw sets the fixed-function state it needs and restores GL's defaults afterwards
// (texgen, texture enables, matrices, client arrays, program 0), so shader passes before
// and after are unaffected.

#include "glint/gl/objects.h"
#include "glint/mesh/mesh.h"
#include "glint/core/camera.h"

#include <string_view>

namespace glint::render::env {

class ClassicMesh {
public:
  ClassicMesh() = default;
  explicit ClassicMesh(const Mesh& mesh, std::string_view label = "classic-mesh");
  /// glDrawElements with GL_VERTEX_ARRAY and GL_NORMAL_ARRAY client state from the buffer.
  void draw() const;

private:
  gl::Buffer m_vertices;  // interleaved position, normal
  gl::Buffer m_indices;
  GLsizei m_indexCount = 0;
};

class ClassicEnvironment {
public:
  /// Error(NoGpu) unless the current context has the compatibility profile.
  ClassicEnvironment();

  /// A unit cube around the eye with glTexCoord3f = its corner directions: the cube map
  /// seen from the camera's orientation. Depth test and writes off: draw it first.
  void drawSkybox(const gl::Texture& cube, const Camera& camera) const;
  /// GL_REFLECTION_MAP texgen on S, T, R; texture matrix = inverse view rotation; GL_MODULATE
  /// with glColor = tint.
  void drawCubeMapped(const ClassicMesh& mesh, const mat4& model, const Camera& camera, const gl::Texture& cube,
                      vec3 tint = vec3(1.0f)) const;
  /// GL_SPHERE_MAP texgen on S, T with a 2D sphere map made for this camera's view.
  void drawSphereMapped(const ClassicMesh& mesh, const mat4& model, const Camera& camera,
                        const gl::Texture& sphereMap, vec3 tint = vec3(1.0f)) const;
};

}  // namespace glint::render::env
