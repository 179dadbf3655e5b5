#pragma once
// Fixed-width signed integers whose magnitude bound is part of the type.
//
// Int<Bits> holds a value v with |v| < 2^Bits. Arithmetic derives the bound of
// the result statically (a+b: max+1 bits, a*b: sum of bits), so every width used
// by a predicate is checked at compile time: a product that could exceed the
// storage limit (kWideMaxBits) does not compile, and the core's 256-bit budget
// (kMaxBits) is pinned by static_asserts on the predicate types (bounds.hpp). Storage is the narrowest two's-complement
// representation: int64 for Bits <= 63, __int128 for Bits <= 127, otherwise
// 64-bit limbs (little endian). No division, no heap, all constexpr-capable.
#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>
#include <string>
#include <type_traits>

namespace ember {

using i128 = __int128;
using u128 = unsigned __int128;

/// The budget of the Boolean core: every predicate of the geometry layer fits
/// a 256-bit two's-complement integer (|v| < 2^255); bounds.hpp and the core's
/// predicates static_assert their widths against it.
inline constexpr int kMaxBits = 255;
/// Largest magnitude bound the type itself supports. Only the output stage goes
/// past kMaxBits: comparing coordinates of two computed points (351 bits) and
/// the orientation of three computed points in a plane (541 bits) run once per
/// output vertex or triangulation step, behind floating-point filters
/// (geometry/exact_order.hpp).
inline constexpr int kWideMaxBits = 575;

namespace detail {
/// Limbs needed for a magnitude of Bits bits plus the sign bit.
constexpr int limbs_for(int bits) { return (bits + 1 + 63) / 64; }
constexpr int max_int(int a, int b) { return a > b ? a : b; }
}  // namespace detail

/// Correctly rounded conversion. Most values fit 64 bits; converting those
/// skips libgcc's __int128 routine (both conversions round correctly, so the
/// result is the same).
inline double to_double(i128 v) {
  const auto low = static_cast<std::int64_t>(v);
  return static_cast<i128>(low) == v ? static_cast<double>(low) : static_cast<double>(v);
}

/// An approximation within 3 roundings (relative error < 2^-51), without
/// libgcc's __int128 routine (~50 instructions for values above 2^64), for
/// cached approximations that feed filters. Beyond 2^63 the magnitude is
/// split: its high limb (< 2^64) times 2^64, exact unless above 2^53 (one
/// rounding), plus its low limb halved to fit a signed conversion (one
/// rounding, and the lost bit is < 2^-63 of the value), summed (one more).
/// Requires v > -2^127 (the high limb of |v| then fits int64).
inline double approx_to_double(i128 v) {
  assert(v != static_cast<i128>(static_cast<u128>(1) << 127));
  const u128 m = v < 0 ? -static_cast<u128>(v) : static_cast<u128>(v);
  const double r = (m >> 63) == 0
                       ? static_cast<double>(static_cast<std::int64_t>(m))
                       : static_cast<double>(static_cast<std::int64_t>(m >> 64)) * 0x1p64 +
                             static_cast<double>(static_cast<std::int64_t>(static_cast<std::uint64_t>(m) >> 1)) * 2.0;
  return v < 0 ? -r : r;
}

template <int Bits>
class Int;

template <typename T>
struct is_int : std::false_type {};
template <int B>
struct is_int<Int<B>> : std::true_type {};

template <int Bits>
class Int {
  static_assert(Bits >= 1 && Bits <= kWideMaxBits, "Int<Bits>: magnitude bound must be in [1, 575] bits");

 public:
  static constexpr int bits = Bits;
  static constexpr int limbs = detail::limbs_for(Bits);
  using Storage = std::conditional_t<limbs == 1, std::int64_t,
                                     std::conditional_t<limbs == 2, i128, std::array<std::uint64_t, limbs>>>;

  constexpr Int() : v_{} {}

  /// From a machine integer. The caller guarantees |v| < 2^Bits (checked in debug builds).
  template <typename T, typename = std::enable_if_t<std::is_integral_v<T> || std::is_same_v<T, i128>>>
  constexpr Int(T v) {  // NOLINT(google-explicit-constructor): literals are common in predicates
    if constexpr (limbs == 1) {
      v_ = static_cast<std::int64_t>(v);
    } else if constexpr (limbs == 2) {
      v_ = static_cast<i128>(v);
    } else {
      const i128 w = static_cast<i128>(v);
      v_[0] = static_cast<std::uint64_t>(w);
      v_[1] = static_cast<std::uint64_t>(w >> 64);
      for (int i = 2; i < limbs; ++i) v_[i] = w < 0 ? ~std::uint64_t{0} : 0;
    }
    assert(fits_bound());
  }

  /// Widening from a smaller bound is implicit and exact.
  template <int B, typename = std::enable_if_t<(B < Bits)>>
  constexpr Int(const Int<B>& o) {  // NOLINT(google-explicit-constructor)
    if constexpr (limbs == 1) {
      v_ = o.raw();
    } else if constexpr (limbs == 2) {
      v_ = static_cast<i128>(o.raw());
    } else {
      for (int i = 0; i < limbs; ++i) v_[i] = o.limb(i);
    }
  }

  /// Tightens the static bound where an argument outside the type system (e.g. a
  /// geometric area bound) proves |o| < 2^Bits. Checked in debug builds.
  template <int B>
  static constexpr Int assume_bound(const Int<B>& o) {
    Int r;
    if constexpr (limbs == 1) {
      r.v_ = static_cast<std::int64_t>(o.limb(0));
    } else if constexpr (limbs == 2) {
      r.v_ = static_cast<i128>((static_cast<u128>(o.limb(1)) << 64) | o.limb(0));
    } else {
      for (int i = 0; i < limbs; ++i) r.v_[i] = o.limb(i);
    }
    assert(r.fits_bound() && r == Int<detail::max_int(B, Bits)>(o));
    return r;
  }

  static constexpr Int from_limbs(const std::array<std::uint64_t, limbs>& l) {
    Int r;
    if constexpr (limbs == 1) {
      r.v_ = static_cast<std::int64_t>(l[0]);
    } else if constexpr (limbs == 2) {
      r.v_ = static_cast<i128>((static_cast<u128>(l[1]) << 64) | l[0]);
    } else {
      r.v_ = l;
    }
    return r;
  }

  /// Limb i of the two's-complement representation, sign-extended past the storage.
  constexpr std::uint64_t limb(int i) const {
    if constexpr (limbs == 1) {
      return i == 0 ? static_cast<std::uint64_t>(v_) : (v_ < 0 ? ~std::uint64_t{0} : 0);
    } else if constexpr (limbs == 2) {
      if (i == 0) return static_cast<std::uint64_t>(v_);
      if (i == 1) return static_cast<std::uint64_t>(static_cast<u128>(v_) >> 64);
      return v_ < 0 ? ~std::uint64_t{0} : 0;
    } else {
      if (i < limbs) return v_[i];
      return negative() ? ~std::uint64_t{0} : 0;
    }
  }

  constexpr const Storage& raw() const { return v_; }

  constexpr bool negative() const {
    if constexpr (limbs <= 2) {
      return v_ < 0;
    } else {
      return static_cast<std::int64_t>(v_[limbs - 1]) < 0;
    }
  }
  constexpr bool is_zero() const {
    if constexpr (limbs <= 2) {
      return v_ == 0;
    } else {
      std::uint64_t acc = 0;
      for (int i = 0; i < limbs; ++i) acc |= v_[i];
      return acc == 0;
    }
  }
  /// -1, 0 or +1.
  constexpr int sign() const { return negative() ? -1 : (is_zero() ? 0 : 1); }

  constexpr Int operator-() const {
    Int r;
    if constexpr (limbs <= 2) {
      r.v_ = -v_;
    } else {
      std::uint64_t carry = 1;
      for (int i = 0; i < limbs; ++i) {
        const std::uint64_t x = ~v_[i] + carry;
        carry = (carry && x == 0) ? 1 : 0;
        r.v_[i] = x;
      }
    }
    return r;
  }

  constexpr Int abs() const { return negative() ? -*this : *this; }

  /// Approximate value (round-to-nearest per limb; relative error ≤ 2^-52).
  double to_double() const {
    if constexpr (limbs == 1) {
      return static_cast<double>(v_);
    } else if constexpr (limbs == 2) {
      return ember::to_double(v_);
    } else {
      const Int m = abs();
      double r = 0;
      for (int i = limbs - 1; i >= 0; --i) r = r * 18446744073709551616.0 + static_cast<double>(m.v_[i]);
      return negative() ? -r : r;
    }
  }

  /// Decimal representation (for messages and tests; not on any hot path).
  std::string to_string() const {
    const bool neg = negative();
    std::array<std::uint64_t, limbs> mag{};
    const Int m = abs();
    for (int i = 0; i < limbs; ++i) mag[i] = m.limb(i);
    std::string digits;
    auto nonzero = [&] { return std::any_of(mag.begin(), mag.end(), [](std::uint64_t x) { return x != 0; }); };
    if (!nonzero()) return "0";
    while (nonzero()) {
      u128 rem = 0;
      for (int i = limbs - 1; i >= 0; --i) {
        const u128 cur = (rem << 64) | mag[i];
        mag[i] = static_cast<std::uint64_t>(cur / 10);
        rem = cur % 10;
      }
      digits.push_back(static_cast<char>('0' + static_cast<int>(rem)));
    }
    if (neg) digits.push_back('-');
    return {digits.rbegin(), digits.rend()};
  }

  /// True iff |value| < 2^Bits (the invariant of the type).
  constexpr bool fits_bound() const {
    const Int m = abs();  // -(-2^(64L-1)) wraps, then reads negative: caught below
    if (m.negative()) return false;
    for (int i = limbs - 1; i >= 0; --i) {
      const std::uint64_t l = m.limb(i);
      const int lo = 64 * i;
      if (lo + 64 <= Bits) return true;  // all remaining bits are allowed
      const int allowed = Bits - lo;     // bits of this limb that may be set
      if (allowed <= 0) {
        if (l != 0) return false;
      } else if ((l >> allowed) != 0) {
        return false;
      }
    }
    return true;
  }

 private:
  template <int>
  friend class Int;
  Storage v_;
};

// ---- addition / subtraction: |a ± b| < 2^max(A,B) + 2^max(A,B) = 2^(max+1) ----

namespace detail {
template <int R, int A, int B, bool Subtract>
constexpr Int<R> add_sub(const Int<A>& a, const Int<B>& b) {
  static_assert(R <= kWideMaxBits, "sum exceeds the 576-bit storage limit");
  constexpr int L = Int<R>::limbs;
  if constexpr (L == 1) {
    return Int<R>(Subtract ? static_cast<std::int64_t>(a.raw()) - static_cast<std::int64_t>(b.raw())
                           : static_cast<std::int64_t>(a.raw()) + static_cast<std::int64_t>(b.raw()));
  } else if constexpr (L == 2) {
    const i128 x = static_cast<i128>(a.raw()), y = static_cast<i128>(b.raw());
    return Int<R>::assume_bound(Int<127>(Subtract ? x - y : x + y));
  } else {
    std::array<std::uint64_t, L> out{};
    std::uint64_t carry = Subtract ? 1 : 0;  // a - b = a + ~b + 1
    for (int i = 0; i < L; ++i) {
      const std::uint64_t y = Subtract ? ~b.limb(i) : b.limb(i);
      const u128 s = static_cast<u128>(a.limb(i)) + y + carry;
      out[i] = static_cast<std::uint64_t>(s);
      carry = static_cast<std::uint64_t>(s >> 64);
    }
    return Int<R>::from_limbs(out);
  }
}

/// Unsigned magnitude of a value as N limbs (N >= the limbs its magnitude needs).
template <int N, int A>
constexpr std::array<std::uint64_t, N> magnitude(const Int<A>& a) {
  std::array<std::uint64_t, N> m{};
  const Int<A> x = a.abs();
  for (int i = 0; i < N; ++i) m[i] = x.limb(i);
  return m;
}
constexpr int mag_limbs(int bits) { return (bits + 63) / 64; }
}  // namespace detail

template <int A, int B>
constexpr Int<detail::max_int(A, B) + 1> operator+(const Int<A>& a, const Int<B>& b) {
  return detail::add_sub<detail::max_int(A, B) + 1, A, B, false>(a, b);
}
template <int A, int B>
constexpr Int<detail::max_int(A, B) + 1> operator-(const Int<A>& a, const Int<B>& b) {
  return detail::add_sub<detail::max_int(A, B) + 1, A, B, true>(a, b);
}

// ---- multiplication: |a·b| < 2^A · 2^B = 2^(A+B) ----

template <int A, int B>
constexpr Int<A + B> operator*(const Int<A>& a, const Int<B>& b) {
  constexpr int R = A + B;
  static_assert(R <= kWideMaxBits, "product exceeds the 576-bit storage limit");
  if constexpr (R <= 63) {
    return Int<R>(static_cast<std::int64_t>(a.raw()) * static_cast<std::int64_t>(b.raw()));
  } else if constexpr (R <= 127) {
    // The true product fits i128, so the product mod 2^128 (computed unsigned to
    // avoid signed overflow in discarded high bits) is exact, whatever limbs the
    // operands use. Replaces the limb loop for e.g. Int<106>*Int<21>.
    const u128 p = static_cast<u128>(static_cast<i128>(a.raw())) * static_cast<u128>(static_cast<i128>(b.raw()));
    return Int<R>::assume_bound(Int<127>(static_cast<i128>(p)));
  } else if constexpr (Int<B>::limbs == 1) {
    return b * a;  // the one-limb factor first (below)
  } else if constexpr (Int<A>::limbs == 1) {
    // One factor is an int64 (|a| < 2^63): b's two's-complement limbs times
    // a, lowest first, with a signed carry (the top limb is b's signed one).
    // Each step |a * limb + carry| < 2^63 * 2^64 + 2^63 < 2^127 fits an
    // i128; no magnitudes, no sign branches, no final negation. The plane
    // coefficients (53 bits) times minors and point coordinates in Cramer's
    // rule and in classify are of this kind.
    constexpr int LB = Int<B>::limbs, LR = Int<R>::limbs;
    static_assert(LB <= LR, "the product has at least the limbs of its wider factor");
    const i128 x = a.raw();
    std::array<std::uint64_t, LR> out{};
    i128 carry = 0;
    for (int j = 0; j < LB; ++j) {
      const i128 limb =
          j + 1 < LB ? static_cast<i128>(b.limb(j)) : static_cast<i128>(static_cast<std::int64_t>(b.limb(j)));
      const i128 t = x * limb + carry;
      out[j] = static_cast<std::uint64_t>(t);
      carry = t >> 64;  // arithmetic: floor
    }
    for (int j = LB; j < LR; ++j) {  // sign extension of the last carry
      out[j] = static_cast<std::uint64_t>(carry);
      carry >>= 64;
    }
    return Int<R>::from_limbs(out);
  } else {
    // Both factors of two or more limbs. (A branch-free variant, correcting an
    // unsigned product of the two's-complement limbs by masked subtractions of the
    // other operand, is slower for Int<53>*Int<188>, Int<79>*Int<162>
    // and the classify dot product (faster only for Int<106>*Int<79>): its borrow
    // chains serialize, these sign branches are cheap. The one-limb case above
    // needs no correction: its factor's sign rides in the signed products.)
    // Schoolbook product of magnitudes, then the sign. Magnitudes need ceil(A/64)
    // limbs; the result needs ceil(R/64) limbs and cannot carry past them.
    constexpr int LA = detail::mag_limbs(A), LB = detail::mag_limbs(B);
    constexpr int LR = Int<R>::limbs;
    const auto ma = detail::magnitude<LA>(a);
    const auto mb = detail::magnitude<LB>(b);
    std::array<std::uint64_t, LR> out{};
    for (int i = 0; i < LA; ++i) {
      std::uint64_t carry = 0;
      for (int j = 0; j < LB && i + j < LR; ++j) {
        const u128 t = static_cast<u128>(ma[i]) * mb[j] + out[i + j] + carry;
        out[i + j] = static_cast<std::uint64_t>(t);
        carry = static_cast<std::uint64_t>(t >> 64);
      }
      if (i + LB < LR) out[i + LB] = carry;
    }
    const Int<R> r = Int<R>::from_limbs(out);
    return (a.negative() != b.negative()) ? -r : r;
  }
}

// ---- comparison ----

template <int A, int B>
constexpr bool operator==(const Int<A>& a, const Int<B>& b) {
  constexpr int L = detail::max_int(Int<A>::limbs, Int<B>::limbs);
  for (int i = 0; i < L; ++i)
    if (a.limb(i) != b.limb(i)) return false;
  return true;
}
/// -1, 0 or +1. Compares limbs directly (top limb signed, the rest unsigned) so
/// no wider difference is formed: works for any width and needs no carry chain.
template <int A, int B>
constexpr int compare(const Int<A>& a, const Int<B>& b) {
  if constexpr (Int<A>::limbs == 1 && Int<B>::limbs == 1) {
    return (a.raw() > b.raw()) - (a.raw() < b.raw());
  } else if constexpr (Int<A>::limbs <= 2 && Int<B>::limbs <= 2) {
    const i128 x = a.raw(), y = b.raw();
    return (x > y) - (x < y);
  } else {
    constexpr int L = detail::max_int(Int<A>::limbs, Int<B>::limbs);
    const auto ta = static_cast<std::int64_t>(a.limb(L - 1)), tb = static_cast<std::int64_t>(b.limb(L - 1));
    if (ta != tb) return ta < tb ? -1 : 1;
    for (int i = L - 2; i >= 0; --i)
      if (a.limb(i) != b.limb(i)) return a.limb(i) < b.limb(i) ? -1 : 1;
    return 0;
  }
}
template <int A, int B>
constexpr bool operator<(const Int<A>& a, const Int<B>& b) {
  return compare(a, b) < 0;
}
template <int A, int B>
constexpr bool operator>(const Int<A>& a, const Int<B>& b) {
  return compare(a, b) > 0;
}
template <int A, int B>
constexpr bool operator<=(const Int<A>& a, const Int<B>& b) {
  return compare(a, b) <= 0;
}
template <int A, int B>
constexpr bool operator>=(const Int<A>& a, const Int<B>& b) {
  return compare(a, b) >= 0;
}

/// Sign of a·b − c·d without forming more than needed (common 2×2 minor).
template <int A, int B, int C, int D>
constexpr auto det2(const Int<A>& a, const Int<B>& b, const Int<C>& c, const Int<D>& d) {
  return a * b - c * d;
}

}  // namespace ember
