#pragma once
// KEYTURN_UNDER_ASAN: defined when this file is compiled with AddressSanitizer (GCC's macro or
// Clang's feature test), for the tests whose subject ASan changes (its own signal reports, its
// slower frames, PCL's mismatched frees).
#if defined(__SANITIZE_ADDRESS__)
#define KEYTURN_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define KEYTURN_UNDER_ASAN 1
#endif
#endif
