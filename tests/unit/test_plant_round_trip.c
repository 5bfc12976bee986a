#include "unity.h"
#include "platform_fixture.h"
int main(void) { UNITY_BEGIN(); return UNITY_END(); }
