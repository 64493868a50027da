#include <cstdio>
int main() { std::puts("wedge: under construction"); return 0; }
