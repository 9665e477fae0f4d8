// polarview entry point (placeholder until the CLI lands).
#include <cstdio>
int main() { std::puts("polarview"); return 0; }
