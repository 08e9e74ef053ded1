// The stored polynomial tables of the special functions (core/math_tables.h) against MPFR.
//
// tools/math_tables/special.py fits each piece in mpmath and accepts it only if the stored
// coefficients (double-doubles, then doubles) reproduce the function to a relative error below
// 2^-64 at 128 evenly spaced points of the piece. This program repeats that acceptance test
// independently: it evaluates every stored piece exactly (Horner in 256-bit MPFR arithmetic on
// the stored doubles) at the same points and compares it with MPFR's own function. A damaged
// coefficient — even the low word of a double-double, worth 2^-106 of it — shows here long
// before it moves a rounded result, which only happens near a rounding midpoint. Tang's table
// 2^(j/128) = hi + lo is checked to 2^-104 relative, and each of its entries to be normalised.
//
// Usage: math_tables_check   (exit 0: every piece within its bound; 1: a failure, printed)
#include <mpfr.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>

#include "core/math_tables.h"

namespace {

namespace tables = oceanref::math::tables;
constexpr mpfr_prec_t kBits = 256;
constexpr int kSamples = 128;  // as tools/math_tables/special.py samples each piece

// RAII for one MPFR variable at kBits.
struct Real {
  mpfr_t v;
  Real() { mpfr_init2(v, kBits); }
  explicit Real(double d) : Real() { mpfr_set_d(v, d, MPFR_RNDN); }
  ~Real() { mpfr_clear(v); }
  Real(const Real&) = delete;
  Real& operator=(const Real&) = delete;
};

// The function a table approximates at x (see core/math_tables.h), in MPFR.
void table_function(const char* name, const Real& x, Real& out) {
  Real a, b;
  if (std::strcmp(name, "erf_small") == 0) {  // erf(√u)/√u, 2/√π at u = 0
    if (mpfr_zero_p(x.v)) {
      mpfr_const_pi(a.v, MPFR_RNDN);
      mpfr_sqrt(a.v, a.v, MPFR_RNDN);
      mpfr_ui_div(out.v, 2, a.v, MPFR_RNDN);
      return;
    }
    mpfr_sqrt(a.v, x.v, MPFR_RNDN);
    mpfr_erf(b.v, a.v, MPFR_RNDN);
    mpfr_div(out.v, b.v, a.v, MPFR_RNDN);
  } else if (std::strcmp(name, "erf") == 0) {
    mpfr_erf(out.v, x.v, MPFR_RNDN);
  } else if (std::strcmp(name, "erfcx") == 0) {  // e^{x²} erfc x
    mpfr_erfc(a.v, x.v, MPFR_RNDN);
    mpfr_sqr(b.v, x.v, MPFR_RNDN);
    mpfr_exp(b.v, b.v, MPFR_RNDN);
    mpfr_mul(out.v, a.v, b.v, MPFR_RNDN);
  } else if (std::strcmp(name, "lgamma") == 0 || std::strcmp(name, "lgamma_neg_zero") == 0) {
    int sign = 0;  // ln|Γ(x)|
    mpfr_lgamma(out.v, &sign, x.v, MPFR_RNDN);
  } else if (std::strcmp(name, "stirling") == 0) {  // W(z) with X = 1/√z; 1/12 at z = 0
    if (mpfr_zero_p(x.v)) {
      mpfr_set_ui(out.v, 1, MPFR_RNDN);
      mpfr_div_ui(out.v, out.v, 12, MPFR_RNDN);
      return;
    }
    Real big, c;
    mpfr_rec_sqrt(big.v, x.v, MPFR_RNDN);  // X
    int sign = 0;
    mpfr_lgamma(a.v, &sign, big.v, MPFR_RNDN);  // ln Γ(X)
    mpfr_log(b.v, big.v, MPFR_RNDN);
    mpfr_sub_d(c.v, big.v, 0.5, MPFR_RNDN);
    mpfr_mul(b.v, b.v, c.v, MPFR_RNDN);  // (X − ½) ln X
    mpfr_sub(a.v, a.v, b.v, MPFR_RNDN);
    mpfr_add(a.v, a.v, big.v, MPFR_RNDN);  // + X
    mpfr_const_pi(c.v, MPFR_RNDN);
    mpfr_mul_ui(c.v, c.v, 2, MPFR_RNDN);
    mpfr_log(c.v, c.v, MPFR_RNDN);
    mpfr_div_ui(c.v, c.v, 2, MPFR_RNDN);  // ½ ln 2π
    mpfr_sub(a.v, a.v, c.v, MPFR_RNDN);
    mpfr_mul(out.v, a.v, big.v, MPFR_RNDN);
  } else {
    std::fprintf(stderr, "math_tables_check: no MPFR function for table %s\n", name);
    std::exit(2);
  }
}

// The stored polynomial at t, exactly as stored: Σ c_i t^i with c_i = hi + lo for i < n_dd.
void stored_polynomial(const tables::PieceTable& table, const tables::Piece& p, const Real& t,
                       Real& out) {
  const double* c = table.coefs + p.offset;
  const auto coefficient = [&](int i, Real& r) {
    if (i < p.n_dd) {
      mpfr_set_d(r.v, c[2 * i], MPFR_RNDN);
      mpfr_add_d(r.v, r.v, c[2 * i + 1], MPFR_RNDN);
    } else {
      mpfr_set_d(r.v, c[p.n_dd + i], MPFR_RNDN);
    }
  };
  Real ci;
  mpfr_set_zero(out.v, 1);
  for (int i = p.degree; i >= 0; --i) {
    coefficient(i, ci);
    mpfr_mul(out.v, out.v, t.v, MPFR_RNDN);
    mpfr_add(out.v, out.v, ci.v, MPFR_RNDN);
  }
}

// The largest relative error of one piece over its 128 points (x = centre + t, t from
// x_min − centre to x_max − centre); t = 0 is skipped where the piece is expanded about a zero
// of the function (c_0 = 0), as the generator does.
double piece_error(const tables::PieceTable& table, const tables::Piece& p) {
  Real centre(p.centre_hi), t_lo(p.x_min), t_hi(p.x_max), t, x, fitted, exact, e;
  mpfr_add_d(centre.v, centre.v, p.centre_lo, MPFR_RNDN);
  mpfr_add_d(centre.v, centre.v, p.centre_lo2, MPFR_RNDN);
  mpfr_sub(t_lo.v, t_lo.v, centre.v, MPFR_RNDN);
  mpfr_sub(t_hi.v, t_hi.v, centre.v, MPFR_RNDN);
  const bool zero_piece = table.coefs[p.offset] == 0.0 && table.coefs[p.offset + 1] == 0.0;
  double worst = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    mpfr_sub(t.v, t_hi.v, t_lo.v, MPFR_RNDN);
    mpfr_mul_ui(t.v, t.v, static_cast<unsigned long>(k), MPFR_RNDN);
    mpfr_div_ui(t.v, t.v, kSamples - 1, MPFR_RNDN);
    mpfr_add(t.v, t.v, t_lo.v, MPFR_RNDN);
    if (zero_piece && mpfr_zero_p(t.v)) continue;
    mpfr_add(x.v, centre.v, t.v, MPFR_RNDN);
    stored_polynomial(table, p, t, fitted);
    table_function(table.name, x, exact);
    mpfr_sub(e.v, fitted.v, exact.v, MPFR_RNDN);
    mpfr_div(e.v, e.v, exact.v, MPFR_RNDN);
    worst = std::fmax(worst, std::fabs(mpfr_get_d(e.v, MPFR_RNDN)));
  }
  return worst;
}

}  // namespace

int main() {
  const double bound = 0x1p-64;  // tools/math_tables/special.py's acceptance of a stored piece
  int failures = 0;
  for (const tables::PieceTable& table : tables::special_piece_tables()) {
    double worst = 0.0;
    std::size_t empty = 0;
    for (std::size_t i = 0; i < table.pieces.size(); ++i) {
      const tables::Piece& p = table.pieces[i];
      // A zero of ln|Γ| nearer to an integer than a double's spacing gets a piece that holds
      // no double (x_min > x_max: the generator's [z − r, z + r] between two doubles); it is
      // never looked up, and its polynomial is fitted on a range the piece does not store.
      if (p.x_min > p.x_max) {
        ++empty;
        continue;
      }
      const double e = piece_error(table, p);
      worst = std::fmax(worst, e);
      if (!(e < bound)) {
        std::fprintf(stderr, "FAIL: %s piece %zu [%a, %a]: relative error %.3g >= 2^-64\n",
                     table.name, i, p.x_min, p.x_max, e);
        ++failures;
      }
    }
    std::printf(
        "%-16s %3zu pieces (%zu holding no double), largest relative error %.2e "
        "(2^%.1f)\n",
        table.name, table.pieces.size(), empty, worst, worst > 0.0 ? std::log2(worst) : -HUGE_VAL);
  }
  // Tang's 2^(j/128) = hi + lo: to 2^-104, lo at most half an ulp of hi.
  Real exact, stored;
  double worst = 0.0;
  const std::span<const oceanref::math::dd::DD> powers = tables::exp2_table();
  if (powers.size() != 128) {
    std::fprintf(stderr, "FAIL: the 2^(j/128) table has %zu entries, not 128\n", powers.size());
    ++failures;
  }
  for (std::size_t j = 0; j < powers.size(); ++j) {
    mpfr_set_ui(exact.v, static_cast<unsigned long>(j), MPFR_RNDN);
    mpfr_div_ui(exact.v, exact.v, 128, MPFR_RNDN);
    mpfr_exp2(exact.v, exact.v, MPFR_RNDN);
    mpfr_set_d(stored.v, powers[j].hi, MPFR_RNDN);
    mpfr_add_d(stored.v, stored.v, powers[j].lo, MPFR_RNDN);
    mpfr_sub(stored.v, stored.v, exact.v, MPFR_RNDN);
    mpfr_div(stored.v, stored.v, exact.v, MPFR_RNDN);
    const double e = std::fabs(mpfr_get_d(stored.v, MPFR_RNDN));
    worst = std::fmax(worst, e);
    const bool normalised =
        std::fabs(powers[j].lo) <= 0.5 * (std::nextafter(powers[j].hi, 4.0) - powers[j].hi);
    if (!(e < 0x1p-104) || !normalised) {
      std::fprintf(stderr, "FAIL: 2^(%zu/128) = %a + %a: relative error %.3g%s\n", j, powers[j].hi,
                   powers[j].lo, e, normalised ? "" : ", not normalised");
      ++failures;
    }
  }
  std::printf("%-16s %3zu entries, largest relative error %.2e (2^%.1f)\n", "exp2_table",
              powers.size(), worst, std::log2(worst));
  std::printf("%d failures\n", failures);
  return failures == 0 ? 0 : 1;
}
