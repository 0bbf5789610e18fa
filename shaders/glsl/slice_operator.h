// GLSL only: the body of the operator slicing shader (slice_operator.frag.glsl
// and its _id variant). An operator's proxy (paper section 5.1): the fragment
// is a point p' of the deformed space. Its pre-image comes from the operator's baked map (Eq. 2,
// placed by Eq. 8; Eq. 6: outside the volume or in a cut it is empty), the
// normal is the volume gradient carried through the Jacobian of the map
// (Eq. 5), blended toward the cut's normal within the band D (Eq. 7).
#include "glsl/slice_common.h"
#include "shared/operator_frame.h"

layout(location = 0) in vec3 worldPos;
layout(std140, set = 1, binding = 0) uniform Operator { OperatorUniforms op; };
layout(set = 1, binding = 1) uniform sampler3D operatorMap;

vec4 mapAt(vec3 local) {
    return texture(operatorMap, (local - op.mapLo.xyz) / (op.mapHi.xyz - op.mapLo.xyz));
}

// xyz: the pre-image in the world; w: signed distance to the cut (local units).
vec4 preimage(vec3 world) {
    vec3 q = (op.worldToLocal * vec4(world, 1.0)).xyz;
    vec4 m = mapAt(q);
    return vec4((op.localToWorld * vec4(q + m.xyz, 1.0)).xyz, m.w);
}

bool inVolume(vec3 tc) { return all(greaterThanEqual(tc, vec3(0.0))) && all(lessThanEqual(tc, vec3(1.0))); }

void main() {
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    vec4 src = preimage(worldPos);
    vec3 tc = toTexture(src.xyz);
    if (src.w <= 0.0 || !inVolume(tc)) { // a cut, an opening, or nothing moved here
        emit(vec4(0.0), 0.0);
        return;
    }
    float front = texture(volumeTex, tc).r;
    float back = front;
    vec3 shadePoint = worldPos; // the slab's middle when pre-integrated, as for the background
    if (u.flags.z > 0.5) {
        vec4 srcBack = preimage(worldPos - toEye * stepMm);
        vec3 tcBack = toTexture(srcBack.xyz);
        if (srcBack.w > 0.0 && inVolume(tcBack)) back = texture(volumeTex, tcBack).r;
        shadePoint = worldPos - toEye * (0.5 * stepMm);
    }
    vec4 c = classifySlab(front, back, obliquity);
    if (c.a <= 0.0) {
        emit(vec4(0.0), 0.0);
        return;
    }

    // Jacobian of the continuous backward map and gradient of the cut distance,
    // by central differences over one texel of the map.
    vec4 srcShade = preimage(shadePoint);
    if (srcShade.w <= 0.0) srcShade = src; // the middle fell in the cut: use the front
    vec3 tcShade = toTexture(srcShade.xyz);
    vec3 q = (op.worldToLocal * vec4(shadePoint, 1.0)).xyz;
    float h = op.mapHi.w;
    mat3 jacobian;
    vec3 cutGradient;
    for (int i = 0; i < 3; ++i) {
        vec3 e = vec3(0.0);
        e[i] = h;
        vec4 d = (mapAt(q + e) - mapAt(q - e)) / (2.0 * h);
        vec3 column = d.xyz;
        column[i] += 1.0;
        jacobian[i] = column;
        cutGradient[i] = d.w;
    }
    mat3 a = mat3(op.localToWorld);
    mat3 aInvT = transpose(mat3(op.worldToLocal));
    vec4 g = texture(gradientTex, tcShade);
    vec3 carried = aInvT * (transpose(jacobian) * (transpose(a) * g.xyz)); // Eq. 5
    vec3 cut = aInvT * cutGradient; // points into the material
    float omega = op.band.x > 0.0 ? 1.0 - clamp(srcShade.w / op.band.x, 0.0, 1.0) : 0.0;
    vec4 gradient = vec4(dot(carried, carried) > 1e-12 ? normalize(carried) : vec3(0.0), g.w);
    if (omega > 0.0 && dot(cut, cut) > 1e-12) { // Eq. 7
        vec3 blended = mix(gradient.xyz, normalize(cut), omega);
        gradient = vec4(dot(blended, blended) > 1e-12 ? normalize(blended) : normalize(cut),
                        mix(g.w, 1.0, omega));
    }
    emit(shade(c, gradient, toEye), op.band.y);
}
