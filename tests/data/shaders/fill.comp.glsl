// Writes FILL_VALUE + index into a buffer: proves compute dispatch and define variants.
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Values { uint values[]; };
void main() { values[gl_GlobalInvocationID.x] = FILL_VALUE + gl_GlobalInvocationID.x; }
