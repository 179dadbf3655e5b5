// Placeholder entry point; the real command line arrives with the Boolean core.
#include <cstdio>
int main() {
  std::fprintf(stderr, "ember: not built yet\n");
  return 1;
}
