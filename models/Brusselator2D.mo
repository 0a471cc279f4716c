model Brusselator2D "BRUSS-2D: the 2-D Brusselator reaction-diffusion problem (Hairer-Wanner), N x N periodic grid, 2 N^2 stiff ODEs with a sparse Jacobian"
  parameter Integer N = 32 "grid points per direction";
  parameter Real alpha = 1 "diffusion coefficient";
  parameter Real c = alpha*N^2 "alpha / dx^2, dx = 1/N";
  Real u[N, N](start = {{22*((j - 1)/N)*(1 - (j - 1)/N)^1.5 for j in 1:N} for i in 1:N},
    each fixed = true) "u at x = (i - 1)/N, y = (j - 1)/N";
  Real v[N, N](start = {{27*((i - 1)/N)*(1 - (i - 1)/N)^1.5 for j in 1:N} for i in 1:N},
    each fixed = true) "v at x = (i - 1)/N, y = (j - 1)/N";
equation
  for i in 1:N loop
    for j in 1:N loop
      der(u[i, j]) = 1 + u[i, j]^2*v[i, j] - 4.4*u[i, j] + c*(u[mod(i, N) + 1, j]
        + u[mod(i + N - 2, N) + 1, j] + u[i, mod(j, N) + 1] + u[i, mod(j + N - 2, N) + 1]
        - 4*u[i, j]);
      der(v[i, j]) = 3.4*u[i, j] - u[i, j]^2*v[i, j] + c*(v[mod(i, N) + 1, j]
        + v[mod(i + N - 2, N) + 1, j] + v[i, mod(j, N) + 1] + v[i, mod(j + N - 2, N) + 1]
        - 4*v[i, j]);
    end for;
  end for;
  annotation(experiment(StopTime = 11.5, Tolerance = 1e-6));
end Brusselator2D;
