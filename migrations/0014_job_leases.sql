-- Leases (issue 31): several replicas share one database, and a running job belongs to the
-- replica that claimed it only while its lease lasts. The replica renews the lease while the
-- job runs (its heartbeat); once the lease has expired (the replica died), any replica
-- queues the job again and the next claim takes it. Every write of a job's outcome names
-- its lease owner, so a replica that lost its lease cannot store a second result.
--   lease_owner  the replica that runs the job (a random id per process), NULL when not running
--   lease_until  when the lease expires unless renewed (ISO time, UTC), NULL when not running
ALTER TABLE jobs ADD COLUMN lease_owner TEXT;
ALTER TABLE jobs ADD COLUMN lease_until TEXT;
CREATE INDEX jobs_by_lease ON jobs (status, lease_until);
