/* Siconos plugin of bench/siconos_rocking.py (a benchmark peer; not part of mo2d, compiled by that
   script into a temporary folder): the rocking block's corners A (-b, -h) and B (b, -h) of the
   body frame on the ground y = 0, for two LagrangianScleronomousR relations. q = (x, y, theta) of
   the centre of mass, z = (b, h) (the dynamical system's z). Each relation's output: (the corner's
   height: the normal gap, its x: the tangential position), its Jacobian 2 x 3 column-major
   (Siconos's dense matrices). A Python subclass of LagrangianScleronomousR would need no compiled
   code, but Siconos 4.4 crashes with one (a segmentation fault in
   MoreauJeanOSI::computeFreeOutput at the first step). */
#include <math.h>

static void corner_h(double dx, double dy, const double* q, double* y) {
  const double s = sin(q[2]), c = cos(q[2]);
  y[0] = q[1] + dx * s + dy * c;
  y[1] = q[0] + dx * c - dy * s;
}
static void corner_G(double dx, double dy, const double* q, double* G) {
  const double s = sin(q[2]), c = cos(q[2]);
  G[0] = 0.0;
  G[1] = 1.0; /* column x */
  G[2] = 1.0;
  G[3] = 0.0; /* column y */
  G[4] = dx * c - dy * s;
  G[5] = -dx * s - dy * c; /* column theta */
}
void hA(unsigned int nq, const double* q, unsigned int ny, double* y, unsigned int nz, double* z) {
  (void)nq;
  (void)ny;
  (void)nz;
  corner_h(-z[0], -z[1], q, y);
}
void hB(unsigned int nq, const double* q, unsigned int ny, double* y, unsigned int nz, double* z) {
  (void)nq;
  (void)ny;
  (void)nz;
  corner_h(z[0], -z[1], q, y);
}
void GA(unsigned int nq, const double* q, unsigned int ny, double* G, unsigned int nz, double* z) {
  (void)nq;
  (void)ny;
  (void)nz;
  corner_G(-z[0], -z[1], q, G);
}
void GB(unsigned int nq, const double* q, unsigned int ny, double* G, unsigned int nz, double* z) {
  (void)nq;
  (void)ny;
  (void)nz;
  corner_G(z[0], -z[1], q, G);
}
