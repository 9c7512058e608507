#version 330 core
// Mesh mode: the rasterized (tessellated or given) triangle's object and triangle index.
uniform uint object_id;      // object index + 1; 0 is background
uniform uint primitive_base; // added to gl_PrimitiveID, for meshes drawn in parts
layout(location = 0) out uvec2 item;

void main() { item = uvec2(object_id, primitive_base + uint(gl_PrimitiveID)); }
