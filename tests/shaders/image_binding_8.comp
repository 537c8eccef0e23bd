#version 450
// A storage image at binding 8: past OpenGL's guaranteed image units, so a device with only those
// (or one lowered to them by DeviceConfig::storageImageBindings) must refuse the pipeline.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 8, rgba16f) uniform writeonly image3D volume;

void main() {
    imageStore(volume, ivec3(gl_GlobalInvocationID), vec4(1.0));
}
