#pragma once
// Whether glibc's malloc is this process's heap: on glibc, unless
// AddressSanitizer replaced it. Under ASan glibc's arenas hold nothing, and
// tuning or trimming them (mallopt, malloc_trim) only disturbs glibc's own
// bookkeeping: an arena assertion at thread exit was seen in the sanitizer
// tests. The heap tuners (app/HeapArenas, recon/MemoryHygiene)
// compile to nothing where DFRECON_GLIBC_HEAP is not defined.
#if defined(__GLIBC__)
#define DFRECON_GLIBC_HEAP 1
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#undef DFRECON_GLIBC_HEAP
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#undef DFRECON_GLIBC_HEAP
#endif
#endif
