#pragma once
// The suite also runs under AddressSanitizer and UBSan (`make test-sanitize`), several times
// slower. There the heaviest statistical tests take a quarter of their samples and allow the
// twice larger standard errors that follow, so that every assertion still runs: what that run
// looks for, memory and undefined-behaviour errors, fewer samples find as well. The accuracy the
// tests hold Prism to is the ordinary build's.

namespace prism::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSampleDivisor = 4;
#else
inline constexpr int kSampleDivisor = 1;
#endif
inline constexpr double kErrorScale = kSampleDivisor == 4 ? 2.0 : 1.0;  // √kSampleDivisor

// n samples, or a quarter of them (at least one) under the sanitizers.
constexpr int sanitized_samples(int n) { return n / kSampleDivisor > 0 ? n / kSampleDivisor : 1; }

}  // namespace prism::test
