"""Campaigns: many independent tasks on one executor (:mod:`erdesign.executor`) - batches of records
(:mod:`erdesign.campaign.batch`) and tolerance studies (:mod:`erdesign.campaign.tolerance`)."""
