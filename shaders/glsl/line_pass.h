// GLSL only: what the line passes of the feature bakes share (edt_envelope,
// mask_blur): one invocation per line of voxels along params.axis, the line
// picked by the invocation's xy across that axis.
#ifndef CUTAWAY_LINE_PASS_H
#define CUTAWAY_LINE_PASS_H

// Voxel i of the line at uv.
ivec3 voxel(int i, ivec2 uv) {
    if (params.axis == 0) return ivec3(i, uv.x, uv.y);
    if (params.axis == 1) return ivec3(uv.x, i, uv.y);
    return ivec3(uv.x, uv.y, i);
}

// This invocation's line and its length in voxels; false beyond the grid.
bool invocationLine(out ivec2 uv, out int n) {
    ivec3 dims = params.dims;
    int a = params.axis;
    ivec2 across = a == 0 ? dims.yz : (a == 1 ? dims.xz : dims.xy);
    uv = ivec2(gl_GlobalInvocationID.xy);
    n = dims[a];
    return uv.x < across.x && uv.y < across.y;
}

#endif
