/* Preloaded into the sanitizer build's test runs (./lpv.sh test): dlclose does nothing, so a
 * driver Mesa loads (lavapipe, llvmpipe) stays mapped until exit. LeakSanitizer checks at exit; a
 * leak whose stack runs through an unloaded module shows only "<unknown module>" frames, which no
 * suppression can name. Kept loaded, Mesa's one leak is named and suppressed (tests/lsan.supp). */
int dlclose(void* handle) {
    (void)handle;
    return 0;
}
