/*
 * SUNDIALS IDA side of the unimo comparison: ROBER (as a DAE), HIRES and VDPOL
 * (as implicit ODEs F = y' - f(y) = 0).
 *
 * Dense direct linear solver (SUNLinSol_Dense on a SUNDenseMatrix) with an ANALYTIC
 * Jacobian dF/dy + cj dF/dy' (IDASetJacFn); pass "dq" as the 3rd argument to use
 * IDA's internal difference-quotient Jacobian instead. Scalar tolerances
 * (IDASStolerances). All other options are IDA's defaults, except the maximum number
 * of steps per IDASolve call, raised from 500 to 10^8 because the whole interval is
 * integrated in one call (one output point, the end time, with IDASetStopTime).
 * Consistent initial y and y' are given directly (no IDACalcIC).
 *
 * Usage: ida_compare [RUNS] [PROBLEM|all] [analytic|dq]   or   ida_compare version
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
#include <sunmatrix/sunmatrix_dense.h>

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

/* ---------------- HIRES -------------------------------------------------------- */
static void hires_f(const double *x, double *y) {
  y[0] = -1.71 * x[0] + 0.43 * x[1] + 8.32 * x[2] + 0.0007;
  y[1] = 1.71 * x[0] - 8.75 * x[1];
  y[2] = -10.03 * x[2] + 0.43 * x[3] + 0.035 * x[4];
  y[3] = 8.32 * x[1] + 1.71 * x[2] - 1.12 * x[3];
  y[4] = -1.745 * x[4] + 0.43 * x[5] + 0.43 * x[6];
  y[5] = -280.0 * x[5] * x[7] + 0.69 * x[3] + 1.71 * x[4] - 0.43 * x[5] + 0.69 * x[6];
  y[6] = 280.0 * x[5] * x[7] - 1.81 * x[6];
  y[7] = -280.0 * x[5] * x[7] + 1.81 * x[6];
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
  fy[0][0] = -1.71; fy[0][1] = 0.43; fy[0][2] = 8.32;
  fy[1][0] = 1.71; fy[1][1] = -8.75;
  fy[2][2] = -10.03; fy[2][3] = 0.43; fy[2][4] = 0.035;
  fy[3][1] = 8.32; fy[3][2] = 1.71; fy[3][3] = -1.12;
  fy[4][4] = -1.745; fy[4][5] = 0.43; fy[4][6] = 0.43;
  fy[5][3] = 0.69; fy[5][4] = 1.71; fy[5][5] = -280.0 * x[7] - 0.43; fy[5][6] = 0.69;
  fy[5][7] = -280.0 * x[5];
  fy[6][5] = 280.0 * x[7]; fy[6][6] = -1.81; fy[6][7] = 280.0 * x[5];
  fy[7][5] = -280.0 * x[7]; fy[7][6] = 1.81; fy[7][7] = -280.0 * x[5];
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

typedef struct {
  const char *name, *key;
  int n;
  double t_end, atol_factor;
  const double *ref;
  IDAResFn res;
  IDALsJacFn jac;
  void (*init)(double *, double *);
} Problem;

static const Problem PROBLEMS[] = {
    {"ROBER", "rober", 3, 1e11, 1e-6, ROBER_REF, rober_res, rober_jac, rober_init},
    {"HIRES", "hires", 8, 321.8122, 1e-2, HIRES_REF, hires_res, hires_jac, hires_init},
    {"VDPOL", "vdpol", 2, 2.0, 1e-2, VDPOL_REF, vdpol_res, vdpol_jac, vdpol_init},
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
  double y[8];
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
  SUNMatrix A = SUNDenseMatrix(p->n, p->n, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(yy, A, ctx);
  IDASetLinearSolver(mem, LS, A);
  if (!dq) IDASetJacFn(mem, p->jac);
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

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "version") == 0) {
    printf("SUNDIALS %s (IDA)\n", SUNDIALS_VERSION);
    return 0;
  }
  int runs = argc > 1 ? atoi(argv[1]) : 5;
  const char *which = argc > 2 ? argv[2] : "all";
  int dq = argc > 3 && strcmp(argv[3], "dq") == 0;
  if (runs < 1) runs = 1;
  SUNContext ctx;
  SUNContext_Create(NULL, &ctx);
  const double rtols[4] = {1e-4, 1e-6, 1e-8, 1e-10};
  double *times = malloc(sizeof(double) * runs);
  for (size_t k = 0; k < sizeof PROBLEMS / sizeof PROBLEMS[0]; k++) {
    const Problem *p = &PROBLEMS[k];
    if (strcmp(which, "all") != 0 && strcmp(which, p->key) != 0) continue;
    for (int i = 0; i < 4; i++) {
      double rtol = rtols[i], atol = rtol * p->atol_factor;
      Outcome o;
      last_error[0] = 0;
      for (int r = 0; r < runs; r++) {
        double t0 = now_ms();
        o = run_once(ctx, p, rtol, atol, dq);
        times[r] = now_ms() - t0;
      }
      qsort(times, runs, sizeof(double), cmp);
      double median = times[runs / 2];
      const char *method = dq ? "BDF (dense, DQ Jacobian)" : "BDF (dense, analytic Jacobian)";
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
        for (int j = 0; j < p->n; j++) fprintf(stderr, " %.16e", o.y[j]);
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
