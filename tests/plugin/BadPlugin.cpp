// Libraries `fovea --plugin` must refuse (tests/cli/CliPluginTests.cpp), one per kind of
// refusal, selected by a definition. They include no fovea header: each defines only what its
// refusal needs, so they build in a moment.
#if defined(FOVEA_BAD_PLUGIN_WRONG_ABI)
// Built against "another fovea": the ABI string differs, so fovea_plugin_register never runs.
extern "C" const char* fovea_plugin_abi() {
    return "fovea 0.0.1 plugin-abi 0 cxx11-abi 1";
}
extern "C" void fovea_plugin_register(void*) {}
#elif defined(FOVEA_BAD_PLUGIN_NO_ENTRY)
// A shared library, but not a fovea plugin.
extern "C" int fovea_unrelated_function() {
    return 42;
}
#elif defined(FOVEA_BAD_PLUGIN_UNDEFINED_SYMBOL)
// Needs a symbol neither fovea nor any library defines: dlopen(RTLD_NOW) refuses it by name.
extern "C" void fovea_symbol_nobody_defines();
extern "C" void fovea_plugin_register(void*) {
    fovea_symbol_nobody_defines();
}
#else
#error "define one FOVEA_BAD_PLUGIN_* kind"
#endif
