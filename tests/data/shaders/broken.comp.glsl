// A compute shader with an error on line 5 of an included file (tests the file:line mapping).
#include "broken_include.glsl"
layout(local_size_x = 1) in;
void main() { helper(); }
