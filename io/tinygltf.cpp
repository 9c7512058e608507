// tinygltf's implementation, compiled here rather than linked from Debian's libtinygltf.so: so
// that glint decodes images itself (stb, io/texture_file.h), with a warning where a texture cannot
// be read, and so that the sanitizers and the glTF fuzzer see the parser's code too.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
