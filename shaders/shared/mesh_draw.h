// Push constants of one mesh draw (a glTF model or an operator glyph), shared
// by the mesh shaders and render/mesh_pass.cpp. 128 bytes: the least every
// Vulkan device offers.
#ifndef CUTAWAY_MESH_DRAW_H
#define CUTAWAY_MESH_DRAW_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

struct MeshDraw {
    mat4 modelToWorld; ///< the mesh's placement, model units to world mm
    vec4 normal0;      ///< columns of the normal matrix (inverse transpose of the
    vec4 normal1;      ///< placement's 3x3 part), xyz used
    vec4 normal2;
    vec4 color; ///< rgb replaces the vertex colours when w > 0.5
};

CW_NAMESPACE_END

#endif
