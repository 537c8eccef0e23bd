// The GL backend's hazard tracking (GlHazards.h).
#include "GlHazards.h"

namespace lpv::rhi::gl {
namespace {

// The bit that makes a later shader store wait for earlier accesses of a resource of this kind.
GLbitfield storeBit(uint64_t key) {
    return (key >> 32) == 1 ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT : GL_SHADER_STORAGE_BARRIER_BIT;
}

} // namespace

const GlHazards::Write* GlHazards::findWrite(uint64_t key) const {
    for (uint32_t i = 0; i < writeCount_; ++i)
        if (writes_[i].key == key) return &writes_[i];
    return nullptr;
}

const GlHazards::Read* GlHazards::findRead(uint64_t key) const {
    for (uint32_t i = 0; i < readCount_; ++i)
        if (reads_[i].key == key) return &reads_[i];
    return nullptr;
}

GLbitfield GlHazards::beforeRead(uint64_t key, GLbitfield access) const {
    const Write* w = key ? findWrite(key) : nullptr;
    return w && (w->invisible & access) ? access : 0;
}

GLbitfield GlHazards::beforeShaderWrite(uint64_t key, GLbitfield access) const {
    if (!key) return 0;
    const Write* w = findWrite(key);
    return (w && (w->invisible & access)) || findRead(key) ? access : 0;
}

GLbitfield GlHazards::beforeCommandWrite(uint64_t key, GLbitfield access) const {
    if (!key) return 0;
    const Read* r = findRead(key);
    if (r && r->incoherent) return GL_ALL_BARRIER_BITS;
    return beforeRead(key, access);
}

void GlHazards::paid(GLbitfield bits) {
    uint32_t kept = 0;
    for (uint32_t i = 0; i < writeCount_; ++i) {
        Write w = writes_[i];
        w.invisible &= ~bits;
        if (w.invisible) writes_[kept++] = w;
    }
    writeCount_ = kept;
    kept = 0;
    for (uint32_t i = 0; i < readCount_; ++i)
        if (bits != GL_ALL_BARRIER_BITS && !(bits & storeBit(reads_[i].key))) reads_[kept++] = reads_[i];
    readCount_ = kept;
}

bool GlHazards::noteWrite(uint64_t key) {
    if (!key) return true;
    for (uint32_t i = 0; i < writeCount_; ++i)
        if (writes_[i].key == key) {
            writes_[i].invisible = GL_ALL_BARRIER_BITS;
            return true;
        }
    if (writeCount_ == kMaxTracked) return false;
    writes_[writeCount_++] = {key, GL_ALL_BARRIER_BITS};
    return true;
}

bool GlHazards::noteRead(uint64_t key, bool incoherent) {
    if (!key) return true;
    for (uint32_t i = 0; i < readCount_; ++i)
        if (reads_[i].key == key) {
            reads_[i].incoherent = reads_[i].incoherent || incoherent;
            return true;
        }
    if (readCount_ == kMaxTracked) return false;
    reads_[readCount_++] = {key, incoherent};
    return true;
}

} // namespace lpv::rhi::gl
