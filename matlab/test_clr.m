% test_clr.m: smoke tests of the clr_mex gateway (run by cargo xtask octave). Prints one "ok"
% or "FAIL" line per check and raises an error at the end when any check failed.
% Needs clr_mex on the path and the working directory at the repository root or
% CLR_PENDULUM_TOML set to the path of tests/data/pendulum.toml.

% Plain MATLAB/Octave syntax (no +=, no script-local functions) so it runs in both.
failures = 0;
tags = {'FAIL', 'ok  '};
report = @(name, pass, detail) fprintf('%s %s (%s)\n', tags{double(logical(pass)) + 1}, name, detail);

% 1. Undamped Hertz law F = K delta^1.5 (elastic code 0 / 'hertz', damping 'none').
K = 1.2e10;                                   % N/m^1.5
delta = [0, 1e-7, 1e-6, 1e-5, 3e-5];          % m
F = clr_mex('normal_force', {'hertz', K, 'none', 1.0}, delta, 0.3, 0.5);
F_ref = K * delta .^ 1.5;
err = max(abs(F - F_ref) ./ max(F_ref, 1));
chk = {'normal_force hertz = K delta^1.5', err < 1e-12, sprintf('max rel err %.2e', err)};
report(chk{:}); failures = failures + ~chk{2};
F0 = clr_mex('normal_force', {0, K, 0, 1.0}, -1e-6, 0.3, 0.5);
chk = {'normal_force zero out of contact', F0 == 0, sprintf('F = %g', F0)};
report(chk{:}); failures = failures + ~chk{2};

% 2. Regularized Coulomb friction: F_T = -mu F_N sign(v_T) beyond v_reg, linear below.
mu = 0.2; v_reg = 1e-3; FN = 50;
FT = clr_mex('friction_force', {'coulomb', [mu, v_reg]}, [-1, -0.5e-3, 0, 0.5e-3, 1], FN);
FT_ref = -mu * FN * [-1, -0.5, 0, 0.5, 1];
err = max(abs(FT - FT_ref));
chk = {'friction_force coulomb', err < 1e-9, sprintf('max abs err %.2e N', err)};
report(chk{:}); failures = failures + ~chk{2};

% 3. Errors carry the clr: identifier and the C ABI message.
try
  clr_mex('friction_force', {'coulomb', [mu]}, 1, FN);
  chk = {'friction_force bad parameters raise', false, 'no error'};
  report(chk{:}); failures = failures + ~chk{2};
catch e
  chk = {'friction_force bad parameters raise', strcmp(e.identifier, 'clr:friction_force'), e.message};
  report(chk{:}); failures = failures + ~chk{2};
end

% 4. Revolute joint: journal pushed 5 um into the wall along +x, frictionless.
r = clr_mex('revolute_forces', [10e-3, 9.9e-3], {'hertz', K, 'none', 1.0}, [], ...
            zeros(1, 6), [1.05e-4, 0, 0, 0, 0, 0], 0.0);
Fr = K * (5e-6) ^ 1.5;
err = abs(r.normal_force - Fr) / Fr + abs(r.journal(1) + Fr) / Fr;
chk = {'revolute_forces', err < 1e-9 && abs(r.penetration - 5e-6) < 1e-15, ...
                   sprintf('F_N = %.6g N, journal fx = %.6g N', r.normal_force, r.journal(1))};
report(chk{:}); failures = failures + ~chk{2};

% 5. run_model on the pendulum model file returns a rod_theta column.
toml_path = getenv('CLR_PENDULUM_TOML');
if isempty(toml_path)
  toml_path = fullfile('tests', 'data', 'pendulum.toml');
end
out = clr_mex('run_model', fileread(toml_path), 1.0);
pass = isfield(out, 'rod_theta') && isfield(out, 't') && numel(out.rod_theta) == numel(out.t) ...
       && numel(out.t) > 1 && abs(out.rod_theta(1) - (-1.0707963267948966)) < 1e-12;
chk = {'run_model pendulum rod_theta', pass, sprintf('%d rows, theta(end) = %.6f rad', ...
                   numel(out.t), out.rod_theta(end))};
report(chk{:}); failures = failures + ~chk{2};

if failures > 0
  error('clr:test', '%d check(s) failed', failures);
end
fprintf('all checks passed\n');
