-- PostgreSQL's version of migrations/0005_machine_coolant.sql: the same schema and seed in PostgreSQL's
-- dialect (src/service/store.rs says how the two sets agree). Append-only, like migrations/.
-- The coolant the programs written for a machine switch on after the spindle starts
-- (core::coolant::Coolant): 'off' (dry, or an air blast the machine runs by itself), 'mist'
-- (M7) or 'flood' (M8). Machines a shop added get 'off' until it says otherwise; the seeded
-- OKK VM-4 gets what seed 004 §3.4 used on it, unless the shop has edited the row.
ALTER TABLE machines ADD COLUMN coolant TEXT NOT NULL DEFAULT 'off' CHECK (coolant IN ('off', 'mist', 'flood'));

UPDATE machines
SET coolant = 'mist',
    reference = reference || '; coolant mist: seed 004 §3.4 (no coolant was used, only oil air mist lubrication at 0.5 MPa near the cutting point, on the VM4-II)'
WHERE seed_key = 'machine:okk-vm4' AND edited = 0;
