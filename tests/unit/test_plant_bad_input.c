#include "unity.h"
int main(void) { UNITY_BEGIN(); return UNITY_END(); }
