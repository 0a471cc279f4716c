/*
 * SUNDIALS IDA side of the unimo comparison: ROBER (as a DAE), HIRES, VDPOL, POLLU and
 * BRUSS2D (as implicit ODEs F = y' - f(y) = 0).
 *
 * ROBER, HIRES, VDPOL, POLLU: dense direct linear solver (SUNLinSol_Dense on a
 * SUNDenseMatrix) with an ANALYTIC Jacobian dF/dy + cj dF/dy' (IDASetJacFn); pass "dq"
 * as the 3rd argument to use IDA's internal difference-quotient Jacobian instead.
 * BRUSS2D (2,048 unknowns): sparse direct solver KLU (SUNLinSol_KLU on a CSC
 * SUNSparseMatrix) with the analytic Jacobian in every mode (IDA's difference quotients
 * need a dense or band matrix), so its "dq" row is not run. Its reference values are read
 * from ../refs/bruss2d.csv (path in the environment variable BRUSS2D_REF, default
 * refs/bruss2d.csv next to the program's directory). Scalar tolerances
 * (IDASStolerances). All other options are IDA's defaults, except the maximum number
 * of steps per IDASolve call, raised from 500 to 10^8 because the whole interval is
 * integrated in one call (one output point, the end time, with IDASetStopTime).
 * Consistent initial y and y' are given directly (no IDACalcIC).
 *
 * Usage: ida_compare [RUNS] [PROBLEM|all] [analytic|dq]   or   ida_compare version
 *        ida_compare solve PROBLEM RTOL ATOL   (one run; the final y as one CSV line,
 *                                               for building references)
 * Prints one tab-separated line per configuration:
 * problem tool method rtol atol scd steps median_ms status
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_version.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#define EPS 1e-6

static const double ROBER_REF[3] = {2.083340149701255e-8, 8.333360770334713e-14,
                                    0.9999999791665050};
static const double HIRES_REF[8] = {7.371312573325668e-4, 1.442485726316185e-4,
                                    5.888729740967575e-5, 1.175651343283149e-3,
                                    2.386356198831331e-3, 6.238968252742796e-3,
                                    2.849998395185769e-3, 2.850001604814231e-3};
static const double VDPOL_REF[2] = {1.706167732170483, -0.8928097010247975};

/* ---------------- ROBER: y1' = -k1 y1 + k3 y2 y3, y2' = k1 y1 - k3 y2 y3 - k2 y2^2,
 *                  0 = y1 + y2 + y3 - 1 -------------------------------------------- */
static int rober_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *d = N_VGetArrayPointer(yp), *r = N_VGetArrayPointer(rr);
  r[0] = d[0] - (-0.04 * y[0] + 1e4 * y[1] * y[2]);
  r[1] = d[1] - (0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1]);
  r[2] = y[0] + y[1] + y[2] - 1.0;
  return 0;
}
static int rober_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                     SUNMatrix J, void *ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double *y = N_VGetArrayPointer(yy);
  SM_ELEMENT_D(J, 0, 0) = cj + 0.04;
  SM_ELEMENT_D(J, 0, 1) = -1e4 * y[2];
  SM_ELEMENT_D(J, 0, 2) = -1e4 * y[1];
  SM_ELEMENT_D(J, 1, 0) = -0.04;
  SM_ELEMENT_D(J, 1, 1) = cj + 1e4 * y[2] + 6e7 * y[1];
  SM_ELEMENT_D(J, 1, 2) = 1e4 * y[1];
  SM_ELEMENT_D(J, 2, 0) = 1.0;
  SM_ELEMENT_D(J, 2, 1) = 1.0;
  SM_ELEMENT_D(J, 2, 2) = 1.0;
  return 0;
}
static void rober_init(double *y, double *yp) {
  y[0] = 1.0; y[1] = 0.0; y[2] = 0.0;
  yp[0] = -0.04; yp[1] = 0.04; yp[2] = 0.0;
}

/* ---------------- HIRES: f = A x + c + s r(x), one reaction r = 280 x6 x8 ------------ */
/* The linear part A as (row, column, coefficient), by rows, and the constant c (row 1). */
static const struct { int i, j; double a; } HIRES_A[] = {
  {0, 0, -1.71}, {0, 1, 0.43}, {0, 2, 8.32},
  {1, 0, 1.71}, {1, 1, -8.75},
  {2, 2, -10.03}, {2, 3, 0.43}, {2, 4, 0.035},
  {3, 1, 8.32}, {3, 2, 1.71}, {3, 3, -1.12},
  {4, 4, -1.745}, {4, 5, 0.43}, {4, 6, 0.43},
  {5, 3, 0.69}, {5, 4, 1.71}, {5, 5, -0.43}, {5, 6, 0.69},
  {6, 6, -1.81},
  {7, 6, 1.81},
};
static const double HIRES_C0 = 0.0007;
/* The reaction's stoichiometry: rows 6 and 8 lose what row 7 gains. */
static const double HIRES_S[8] = {0, 0, 0, 0, 0, -1.0, 1.0, -1.0};
/* Summed in the order of the test set's formulas (the reaction, the linear terms, c), so
 * that IDA's steps are those of the straight-line form to the last bit. */
static void hires_f(const double *x, double *y) {
  /* Unrolled, with the sums in a local array, the table's entries become constants and
   * the sums registers: the straight-line code of the formulas. */
  double r = 280.0 * x[5] * x[7], v[8];
#pragma GCC unroll 8
  for (int i = 0; i < 8; i++) v[i] = HIRES_S[i] != 0.0 ? HIRES_S[i] * r : 0.0;
#pragma GCC unroll 32
  for (size_t k = 0; k < sizeof HIRES_A / sizeof HIRES_A[0]; k++)
    v[HIRES_A[k].i] += HIRES_A[k].a * x[HIRES_A[k].j];
  v[0] += HIRES_C0;
  memcpy(y, v, sizeof v);
}
static int hires_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *d = N_VGetArrayPointer(yp), *r = N_VGetArrayPointer(rr);
  double f[8];
  hires_f(y, f);
  for (int i = 0; i < 8; i++) r[i] = d[i] - f[i];
  return 0;
}
static int hires_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                     SUNMatrix J, void *ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double *x = N_VGetArrayPointer(yy);
  double fy[8][8];
  memset(fy, 0, sizeof fy);
  for (size_t k = 0; k < sizeof HIRES_A / sizeof HIRES_A[0]; k++)
    fy[HIRES_A[k].i][HIRES_A[k].j] = HIRES_A[k].a;
  for (int i = 5; i < 8; i++) { /* d r / d x6 = 280 x8, d r / d x8 = 280 x6 */
    fy[i][5] += HIRES_S[i] * 280.0 * x[7];
    fy[i][7] += HIRES_S[i] * 280.0 * x[5];
  }
  for (int i = 0; i < 8; i++)
    for (int j = 0; j < 8; j++) SM_ELEMENT_D(J, i, j) = (i == j ? cj : 0.0) - fy[i][j];
  return 0;
}
static void hires_init(double *y, double *yp) {
  for (int i = 0; i < 8; i++) y[i] = 0.0;
  y[0] = 1.0; y[7] = 0.0057;
  hires_f(y, yp);
}

/* ---------------- VDPOL: y1' = y2, y2' = ((1 - y1^2) y2 - y1) / eps ------------ */
static int vdpol_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *d = N_VGetArrayPointer(yp), *r = N_VGetArrayPointer(rr);
  r[0] = d[0] - y[1];
  r[1] = d[1] - ((1.0 - y[0] * y[0]) * y[1] - y[0]) / EPS;
  return 0;
}
static int vdpol_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                     SUNMatrix J, void *ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double *y = N_VGetArrayPointer(yy);
  SM_ELEMENT_D(J, 0, 0) = cj;
  SM_ELEMENT_D(J, 0, 1) = -1.0;
  SM_ELEMENT_D(J, 1, 0) = -(-2.0 * y[0] * y[1] - 1.0) / EPS;
  SM_ELEMENT_D(J, 1, 1) = cj - (1.0 - y[0] * y[0]) / EPS;
  return 0;
}
static void vdpol_init(double *y, double *yp) {
  y[0] = 2.0; y[1] = 0.0;
  yp[0] = 0.0; yp[1] = ((1.0 - 4.0) * 0.0 - 2.0) / EPS;
}

/* ---------------- POLLU (test set pollu.f): f = S r(y), r_k = k_k y_a (y_b) ---------- */
static const double POLLU_K[25] = {0.35,   26.6,   1.23e4, 8.6e-4, 8.2e-4, 1.5e4,  1.3e-4,
                                   2.4e4,  1.65e4, 9.0e3,  2.2e-2, 1.2e4,  1.88,   1.63e4,
                                   4.8e6,  3.5e-4, 1.75e-2, 1.0e8, 4.44e11, 1.24e3, 2.1,
                                   5.78,   4.74e-2, 1.78e3, 3.12};
/* Reactants (0-based species; -1: first order). */
static const int POLLU_A[25] = {0, 1, 4, 6, 6, 6, 8, 8, 10, 10, 12, 9, 13,
                                0, 2, 3, 3, 15, 15, 16, 18, 18, 0, 18, 19};
static const int POLLU_B[25] = {-1, 3, 1, -1, -1, 5, -1, 5, 1, 0, -1, 1, -1,
                                5, -1, -1, -1, -1, -1, 5, -1, -1, 3, 0, -1};
/* Net production: up to 5 (species, coefficient) pairs per reaction, species -1 ends. */
static const int POLLU_S[25][5][2] = {
    {{0, -1}, {1, 1}, {2, 1}, {-1, 0}},           {{0, 1}, {1, -1}, {3, -1}, {-1, 0}},
    {{0, 1}, {1, -1}, {4, -1}, {5, 1}, {-1, 0}},  {{4, 2}, {6, -1}, {7, 1}, {-1, 0}},
    {{6, -1}, {7, 1}, {-1, 0}},                   {{4, 1}, {5, -1}, {6, -1}, {7, 1}, {-1, 0}},
    {{4, 1}, {7, 1}, {8, -1}, {9, 1}, {-1, 0}},   {{5, -1}, {8, -1}, {10, 1}, {-1, 0}},
    {{0, 1}, {1, -1}, {9, 1}, {10, -1}, {11, 1}}, {{0, -1}, {10, -1}, {12, 1}, {-1, 0}},
    {{0, 1}, {10, 1}, {12, -1}, {-1, 0}},         {{0, 1}, {1, -1}, {9, -1}, {13, 1}, {-1, 0}},
    {{4, 1}, {6, 1}, {13, -1}, {-1, 0}},          {{0, -1}, {5, -1}, {14, 1}, {-1, 0}},
    {{2, -1}, {3, 1}, {-1, 0}},                   {{3, -1}, {15, 1}, {-1, 0}},
    {{2, 1}, {3, -1}, {-1, 0}},                   {{5, 2}, {15, -1}, {-1, 0}},
    {{2, 1}, {15, -1}, {-1, 0}},                  {{4, 1}, {5, -1}, {16, -1}, {17, 1}, {-1, 0}},
    {{1, 1}, {18, -1}, {-1, 0}},                  {{0, 1}, {2, 1}, {18, -1}, {-1, 0}},
    {{0, -1}, {3, -1}, {18, 1}, {-1, 0}},         {{0, -1}, {18, -1}, {19, 1}, {-1, 0}},
    {{0, 1}, {18, 1}, {19, -1}, {-1, 0}}};
static const double POLLU_REF[20] = {
    0.5646255480022769e-1, 0.1342484130422339,    0.4139734331099427e-8,
    0.5523140207484359e-2, 0.2018977262302196e-6, 0.1464541863493966e-6,
    0.7784249118997964e-1, 0.3245075353396018,    0.7494013383880406e-2,
    0.1622293157301561e-7, 0.1135863833257075e-7, 0.2230505975721359e-2,
    0.2087162882798630e-3, 0.1396921016840158e-4, 0.8964884856898295e-2,
    0.4352846369330103e-17, 0.6899219696263405e-2, 0.1007803037365946e-3,
    0.1772146513969984e-5, 0.5682943292316392e-4};

static void pollu_f(const double *y, double *f) {
  for (int i = 0; i < 20; i++) f[i] = 0.0;
  for (int k = 0; k < 25; k++) {
    double r = POLLU_K[k] * y[POLLU_A[k]] * (POLLU_B[k] < 0 ? 1.0 : y[POLLU_B[k]]);
    for (int m = 0; m < 5 && POLLU_S[k][m][0] >= 0; m++) f[POLLU_S[k][m][0]] += POLLU_S[k][m][1] * r;
  }
}
static int pollu_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *d = N_VGetArrayPointer(yp), *r = N_VGetArrayPointer(rr);
  double f[20];
  pollu_f(y, f);
  for (int i = 0; i < 20; i++) r[i] = d[i] - f[i];
  return 0;
}
static int pollu_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                     SUNMatrix J, void *ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double *y = N_VGetArrayPointer(yy);
  SUNMatZero(J);
  for (int i = 0; i < 20; i++) SM_ELEMENT_D(J, i, i) = cj;
  for (int k = 0; k < 25; k++) {
    int a = POLLU_A[k], b = POLLU_B[k];
    /* d r_k / d y_a and d r_k / d y_b */
    double da = POLLU_K[k] * (b < 0 ? 1.0 : y[b]), db = b < 0 ? 0.0 : POLLU_K[k] * y[a];
    for (int m = 0; m < 5 && POLLU_S[k][m][0] >= 0; m++) {
      int i = POLLU_S[k][m][0];
      double s = POLLU_S[k][m][1];
      SM_ELEMENT_D(J, i, a) -= s * da;
      if (b >= 0) SM_ELEMENT_D(J, i, b) -= s * db;
    }
  }
  return 0;
}
static void pollu_init(double *y, double *yp) {
  for (int i = 0; i < 20; i++) y[i] = 0.0;
  y[1] = 0.2; y[3] = 0.04; y[6] = 0.1; y[7] = 0.3; y[8] = 0.01; y[16] = 0.007;
  pollu_f(y, yp);
}

/* ---------------- BRUSS2D: u, v on an N x N periodic grid; (u, v) of cell (i, j) at
 *                  2 (i N + j), 2 (i N + j) + 1 -------------------------------------- */
#define BN 32
#define BALPHA 1.0
#define BC (BALPHA * BN * BN)
static double BRUSS_REF[2 * BN * BN];
static int wrap(int i) { return (i + BN) % BN; }
static int cell(int i, int j) { return 2 * (wrap(i) * BN + wrap(j)); }
static void bruss_f(const double *x, double *f) {
  for (int i = 0; i < BN; i++)
    for (int j = 0; j < BN; j++) {
      int k = cell(i, j);
      double u = x[k], v = x[k + 1], uuv = u * u * v;
      double lu = x[cell(i + 1, j)] + x[cell(i - 1, j)] + x[cell(i, j + 1)] + x[cell(i, j - 1)] - 4.0 * u;
      double lv = x[cell(i + 1, j) + 1] + x[cell(i - 1, j) + 1] + x[cell(i, j + 1) + 1] +
                  x[cell(i, j - 1) + 1] - 4.0 * v;
      f[k] = 1.0 + uuv - 4.4 * u + BC * lu;
      f[k + 1] = 3.4 * u - uuv + BC * lv;
    }
}
static int bruss_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *d = N_VGetArrayPointer(yp), *r = N_VGetArrayPointer(rr);
  bruss_f(y, r);
  for (int i = 0; i < 2 * BN * BN; i++) r[i] = d[i] - r[i];
  return 0;
}
static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }
/* CSC, 6 entries per column: the unknown itself, its partner in the cell, 4 neighbours. */
static int bruss_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                     SUNMatrix J, void *ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double *x = N_VGetArrayPointer(yy);
  sunindextype *cols = SUNSparseMatrix_IndexPointers(J), *rows = SUNSparseMatrix_IndexValues(J);
  double *vals = SUNSparseMatrix_Data(J);
  int nz = 0;
  for (int i = 0; i < BN; i++)
    for (int j = 0; j < BN; j++)
      for (int s = 0; s < 2; s++) {
        int k = cell(i, j), col = k + s;
        double u = x[k], v = x[k + 1];
        /* dF/dy = cj I - df/dy; entries of column col as (row, value) pairs */
        int r[6] = {col, k + 1 - s, cell(i + 1, j) + s, cell(i - 1, j) + s,
                    cell(i, j + 1) + s, cell(i, j - 1) + s};
        double val[6];
        if (s == 0) { /* column of u: d f_u / du, d f_v / du */
          val[0] = cj - (2.0 * u * v - 4.4 - 4.0 * BC);
          val[1] = -(3.4 - 2.0 * u * v);
        } else { /* column of v: d f_v / dv, d f_u / dv */
          val[0] = cj - (-u * u - 4.0 * BC);
          val[1] = -(u * u);
        }
        for (int m = 2; m < 6; m++) val[m] = -BC;
        /* rows in increasing order */
        int order[6][2];
        for (int m = 0; m < 6; m++) { order[m][0] = r[m]; order[m][1] = m; }
        qsort(order, 6, sizeof order[0], cmp_int);
        cols[col] = nz;
        for (int m = 0; m < 6; m++) {
          rows[nz] = order[m][0];
          vals[nz++] = val[order[m][1]];
        }
      }
  cols[2 * BN * BN] = nz;
  return 0;
}
static void bruss_init(double *y, double *yp) {
  for (int i = 0; i < BN; i++)
    for (int j = 0; j < BN; j++) {
      double gx = (double)i / BN, gy = (double)j / BN;
      y[cell(i, j)] = 22.0 * gy * pow(1.0 - gy, 1.5);
      y[cell(i, j) + 1] = 27.0 * gx * pow(1.0 - gx, 1.5);
    }
  bruss_f(y, yp);
}
/* Reads the reference row (second line after the header) of the CSV. */
static int read_bruss_reference(const char *path) {
  FILE *file = fopen(path, "r");
  if (!file) return -1;
  int c;
  while ((c = fgetc(file)) != EOF && c != '\n') {}
  double t;
  if (fscanf(file, "%lf", &t) != 1) { fclose(file); return -1; }
  for (int i = 0; i < 2 * BN * BN; i++)
    if (fscanf(file, " ,%lf", &BRUSS_REF[i]) != 1) { fclose(file); return -1; }
  fclose(file);
  return 0;
}

typedef struct {
  const char *name, *key;
  int n;
  double t_end, atol_factor;
  const double *ref;
  IDAResFn res;
  IDALsJacFn jac;
  void (*init)(double *, double *);
  int sparse_nonzeros; /* > 0: KLU on a CSC matrix with this many entries */
} Problem;

static const Problem PROBLEMS[] = {
    {"ROBER", "rober", 3, 1e11, 1e-6, ROBER_REF, rober_res, rober_jac, rober_init, 0},
    {"HIRES", "hires", 8, 321.8122, 1e-2, HIRES_REF, hires_res, hires_jac, hires_init, 0},
    {"VDPOL", "vdpol", 2, 2.0, 1e-2, VDPOL_REF, vdpol_res, vdpol_jac, vdpol_init, 0},
    {"POLLU", "pollu", 20, 60.0, 1.0, POLLU_REF, pollu_res, pollu_jac, pollu_init, 0},
    {"BRUSS2D", "bruss2d", 2 * BN * BN, 11.5, 1e-2, BRUSS_REF, bruss_res, bruss_jac,
     bruss_init, 6 * 2 * BN * BN},
};

static char last_error[1024];
static void err_handler(int code, const char *module, const char *function, char *msg,
                        void *ud) {
  (void)ud;
  if (code < 0)
    snprintf(last_error, sizeof last_error, "%s %s: %s", module, function, msg);
}

typedef struct {
  int flag;
  long steps;
  double y[2 * BN * BN];
  double tret;
} Outcome;

static Outcome run_once(SUNContext ctx, const Problem *p, double rtol, double atol, int dq) {
  Outcome o = {0};
  N_Vector yy = N_VNew_Serial(p->n, ctx), yp = N_VNew_Serial(p->n, ctx);
  p->init(N_VGetArrayPointer(yy), N_VGetArrayPointer(yp));
  void *mem = IDACreate(ctx);
  IDASetErrHandlerFn(mem, err_handler, NULL);
  IDAInit(mem, p->res, 0.0, yy, yp);
  IDASStolerances(mem, rtol, atol);
  SUNMatrix A;
  SUNLinearSolver LS;
  if (p->sparse_nonzeros > 0) {
    A = SUNSparseMatrix(p->n, p->n, p->sparse_nonzeros, CSC_MAT, ctx);
    LS = SUNLinSol_KLU(yy, A, ctx);
  } else {
    A = SUNDenseMatrix(p->n, p->n, ctx);
    LS = SUNLinSol_Dense(yy, A, ctx);
  }
  IDASetLinearSolver(mem, LS, A);
  if (!dq || p->sparse_nonzeros > 0) IDASetJacFn(mem, p->jac);
  IDASetMaxNumSteps(mem, 100000000L);
  IDASetStopTime(mem, p->t_end);
  o.flag = IDASolve(mem, p->t_end, &o.tret, yy, yp, IDA_NORMAL);
  IDAGetNumSteps(mem, &o.steps);
  memcpy(o.y, N_VGetArrayPointer(yy), sizeof(double) * p->n);
  IDAFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(yy);
  N_VDestroy(yp);
  return o;
}

static double now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static int load_reference(const Problem *p) {
  if (p->ref != BRUSS_REF) return 0;
  const char *path = getenv("BRUSS2D_REF");
  if (read_bruss_reference(path ? path : "bench/compare/refs/bruss2d.csv") == 0) return 0;
  fprintf(stderr, "cannot read the BRUSS2D reference (set BRUSS2D_REF)\n");
  return -1;
}

static int solve_once(const char *key, double rtol, double atol) {
  SUNContext ctx;
  SUNContext_Create(NULL, &ctx);
  static Outcome o;
  for (size_t k = 0; k < sizeof PROBLEMS / sizeof PROBLEMS[0]; k++) {
    const Problem *p = &PROBLEMS[k];
    if (strcmp(key, p->key) != 0) continue;
    o = run_once(ctx, p, rtol, atol, 0);
    if (o.flag < 0) {
      fprintf(stderr, "%s: %s\n", IDAGetReturnFlagName(o.flag), last_error);
      return 1;
    }
    printf("%.17g", p->t_end);
    for (int j = 0; j < p->n; j++) printf(",%.17g", o.y[j]);
    printf("\n");
    fprintf(stderr, "steps %ld\n", o.steps);
  }
  SUNContext_Free(&ctx);
  return 0;
}

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "version") == 0) {
    printf("SUNDIALS %s (IDA)\n", SUNDIALS_VERSION);
    return 0;
  }
  if (argc > 4 && strcmp(argv[1], "solve") == 0) return solve_once(argv[2], atof(argv[3]), atof(argv[4]));
  int runs = argc > 1 ? atoi(argv[1]) : 5;
  const char *which = argc > 2 ? argv[2] : "all";
  int dq = argc > 3 && strcmp(argv[3], "dq") == 0;
  if (runs < 1) runs = 1;
  SUNContext ctx;
  SUNContext_Create(NULL, &ctx);
  const double rtols[4] = {1e-4, 1e-6, 1e-8, 1e-10};
  double *times = malloc(sizeof(double) * runs);
  static Outcome o; /* 16 KB: not on the stack */
  for (size_t k = 0; k < sizeof PROBLEMS / sizeof PROBLEMS[0]; k++) {
    const Problem *p = &PROBLEMS[k];
    if (strcmp(which, "all") != 0 && strcmp(which, p->key) != 0) continue;
    if (p->sparse_nonzeros > 0 && dq) continue; /* DQ Jacobians need a dense or band matrix */
    if (load_reference(p) != 0) continue;
    for (int i = 0; i < 4; i++) {
      double rtol = rtols[i], atol = rtol * p->atol_factor;
      last_error[0] = 0;
      for (int r = 0; r < runs; r++) {
        double t0 = now_ms();
        o = run_once(ctx, p, rtol, atol, dq);
        times[r] = now_ms() - t0;
      }
      qsort(times, runs, sizeof(double), cmp);
      double median = times[runs / 2];
      const char *method = p->sparse_nonzeros > 0 ? "BDF (sparse KLU, analytic Jacobian)"
                           : dq ? "BDF (dense, DQ Jacobian)"
                                : "BDF (dense, analytic Jacobian)";
      if (o.flag < 0) {
        printf("%s\tIDA\t%s\t%.0e\t%.0e\t-\t%ld\t%.3f\tFAILED: %s at t = %g: %s\n", p->name,
               method, rtol, atol, o.steps, median, IDAGetReturnFlagName(o.flag), o.tret,
               last_error);
      } else {
        double worst = 0.0;
        for (int j = 0; j < p->n; j++) {
          double e = fabs((o.y[j] - p->ref[j]) / p->ref[j]);
          if (isnan(e)) e = INFINITY;
          if (e > worst) worst = e;
        }
        fprintf(stderr, "%s IDA %.0e: y =", p->name, rtol);
        for (int j = 0; j < p->n && j < 20; j++) fprintf(stderr, " %.16e", o.y[j]);
        if (p->n > 20) fprintf(stderr, " ... (%d values)", p->n);
        fprintf(stderr, "\n");
        printf("%s\tIDA\t%s\t%.0e\t%.0e\t%.2f\t%ld\t%.3f\tok\n", p->name, method, rtol, atol,
               -log10(worst), o.steps, median);
      }
      fflush(stdout);
    }
  }
  free(times);
  SUNContext_Free(&ctx);
  return 0;
}
