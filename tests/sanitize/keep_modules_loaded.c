/* Preloaded into the window tests of the sanitizer build (tests/CMakeLists.txt): dlclose() that
 * keeps every module mapped. The X and GLX client libraries that GLFW and libglvnd open at run time
 * keep caches reachable from their own static data; once such a library is unloaded at shutdown,
 * LeakSanitizer no longer sees that data as a root and reports the caches as leaks from an
 * "<unknown module>", which no suppression can name. With the modules kept, LSan scans their data,
 * symbolises their frames, and still reports every allocation that is truly unreachable. */
int dlclose(void* handle) {
    (void)handle;
    return 0;
}
