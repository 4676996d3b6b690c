% journal_impact.m: one journal-bearing impact integrated by Octave/MATLAB's ode15s, with the
% normal force of the clr C ABI (clr_mex 'normal_force') in the right-hand side.
%
% The case is the Rust verification case contact.restitution.ln (xtask/src/verify/contact.rs):
% the flap paper's journal bearing (steel 207 GPa / 0.3, R_i = 10 mm, R_j = 9.9 mm, L = 15 mm,
% radial clearance c = 0.1 mm), the "LN" preset (Hertz internal cylinder + Lankarani-Nikravesh
% damping) with c_e = 0.5, a journal of mass m = 1 kg starting concentric at v0 = 0.5 m/s along
% the line of centres. 1-D: x is the journal's radial position, the penetration is delta = x - c,
% m x'' = -F_N(delta, x', v_in). The free flight is exact (x = v0 t, contact at t0 = c/v0 with
% v_in = v0); ode15s integrates the contact phase to the separation event (delta = 0 falling).
% Prints "restitution = <separation velocity / impact velocity>" for cargo xtask octave.
% Needs clr_mex on the path (docs/matlab.md).

m = 1.0;                 % kg
v0 = 0.5;                % m/s
c_e = 0.5;               % input coefficient of restitution, -
R_i = 10e-3; R_j = 9.9e-3;
c = R_i - R_j;           % radial clearance, m
law = {'LN', c_e};       % flap-paper geometry is the preset's default

t0 = c / v0;             % contact onset, s
v_in = v0;               % impact velocity delta_dot^- (m/s), kept for this contact
rhs = @(t, y) [y(2); -clr_mex('normal_force', law, y(1) - c, y(2), v_in) / m];
% Separation: delta = x - c crosses 0 downwards; terminal.
events = @(t, y) deal(y(1) - c, 1, -1);
opts = odeset('RelTol', 1e-10, 'AbsTol', [1e-16, 1e-12], 'Events', events, ...
              'InitialStep', 1e-9, 'MaxStep', 2e-6);
[t, y, te, ye] = ode15s(rhs, [t0, t0 + 2e-3], [c; v_in], opts);
if isempty(te)
  error('clr:journal_impact', 'no separation within 2 ms');
end
v_out = ye(end, 2);
e = -v_out / v_in;
[~, info] = clr_mex('normal_force', law, 0, 0, v_in);
delta = y(:, 1) - c;
fprintf('solver = ode15s, %d steps\n', numel(t) - 1);
fprintf('contact time = %.6e s, peak penetration = %.6e m\n', te(end) - t0, max(delta));
fprintf('closed_form = %.10f\n', info.effective_restitution);
fprintf('restitution = %.10f\n', e);
