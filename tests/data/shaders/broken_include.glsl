// Included by broken.comp.glsl.

void helper() {
    float x = 1.0;
    x = undefined_name * 2.0;
}
