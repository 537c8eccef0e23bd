// lpv_png_compare A.png B.png TOLERANCE MAX_FRACTION: whether two screenshots show the same image.
// Exit 0 when they have the same size, at most MAX_FRACTION of the pixels differ by more than
// TOLERANCE (of 255, any channel), and A is not blank (a black frame matches another black frame);
// else 1, with the figures either way.
#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace {
using Pixels = std::unique_ptr<unsigned char, decltype(&stbi_image_free)>;

Pixels load(const char* path, int& width, int& height) {
    int channels = 0;
    Pixels pixels(stbi_load(path, &width, &height, &channels, 4), &stbi_image_free);
    if (!pixels) std::fprintf(stderr, "%s: cannot read: %s\n", path, stbi_failure_reason());
    return pixels;
}
} // namespace

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: %s A.png B.png TOLERANCE MAX_FRACTION\n", argv[0]);
        return 2;
    }
    const int tolerance = std::atoi(argv[3]);
    const double maxFraction = std::atof(argv[4]);
    int wa = 0, ha = 0, wb = 0, hb = 0;
    const Pixels a = load(argv[1], wa, ha), b = load(argv[2], wb, hb);
    if (!a || !b) return 1;
    if (wa != wb || ha != hb) {
        std::fprintf(stderr, "sizes differ: %dx%d against %dx%d\n", wa, ha, wb, hb);
        return 1;
    }
    long differing = 0, lit = 0;
    int largest = 0;
    for (long p = 0; p < long(wa) * ha; ++p) {
        int difference = 0;
        for (int c = 0; c < 3; ++c)
            difference = std::max(difference, std::abs(int(a.get()[4 * p + c]) - int(b.get()[4 * p + c])));
        largest = std::max(largest, difference);
        differing += difference > tolerance ? 1 : 0;
        lit += a.get()[4 * p] + a.get()[4 * p + 1] + a.get()[4 * p + 2] > 24 ? 1 : 0;
    }
    const double pixels = double(wa) * ha, fraction = double(differing) / pixels;
    std::printf("%dx%d: %ld pixels (%.3f%%) differ by more than %d of 255, the largest difference %d; "
                "%.1f%% of the pixels lit\n",
                wa, ha, differing, 100.0 * fraction, tolerance, largest, 100.0 * double(lit) / pixels);
    if (double(lit) < 0.25 * pixels) {
        std::fprintf(stderr, "%s is nearly black: nothing to compare\n", argv[1]);
        return 1;
    }
    return fraction <= maxFraction ? 0 : 1;
}
