// The table of engine/render/SpecularAlbedo.h as the renderer uploads it (RGBA16F, kSize texels
// wide, twice that tall): block 0 of rows holds scale, bias and scaleDirection, block 1
// biasDirection and, in z, the Schlick mean (SpecularAlbedo.h's integrateSchlickMean, by cos(light)
// along x, the same in every row). Sampled with bilinear filtering, clamped: texel i of a block holds cos(view) or
// roughness i / (kSize - 1), hence the half-texel inset, which also keeps a block's filtering off
// the other's rows. Shared by the lighting pass, the GI's lookup and its RSMs.
#ifndef SPECULAR_ALBEDO_GLSL
#define SPECULAR_ALBEDO_GLSL

vec4 specularAlbedoAt(sampler2D table, float cosView, float roughness, int block) {
    vec2 size = vec2(textureSize(table, 0));
    vec2 texel = vec2(clamp(cosView, 0.0, 1.0), clamp(roughness, 0.0, 1.0)) * (size.x - 1.0) + 0.5;
    texel.y += float(block) * size.x;
    return textureLod(table, texel / size, 0.0);
}

#endif
